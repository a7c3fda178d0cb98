// `trackbed eval` (see eval_command.h).
#include "eval_command.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "command_errors.h"
#include "trackbed/estimation/per_distance.h"
#include "trackbed/estimation/trajectory_io.h"
#include "trackbed/estimation/trajectory_metrics.h"

namespace trackbed::apps {

namespace {

using namespace trackbed::estimation;

using Json = nlohmann::ordered_json;

std::string Format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), fmt, v);
  return buf;
}

// A JSON string. Kept by hand rather than nlohmann's dump() so that `--json` output stays
// byte-identical: dump() writes backspace, form feed and carriage return as two-character
// escapes where this writes six-character \u ones, and throws on a path that is not UTF-8
// where this copies its bytes through.
std::string Str(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

// One value laid out as `--json` has always printed it, which nlohmann's dump() cannot:
// containers on one line with ", " and ": " separators, and floating-point numbers with
// 10 significant digits (%.10g: "1" rather than dump()'s "1.0", "0.1234567891" rather
// than 17 digits), null when not finite.
void WriteInline(std::ostream& out, const Json& v) {
  if (v.is_object() || v.is_array()) {
    out << (v.is_object() ? '{' : '[');
    const char* separator = "";
    for (auto it = v.begin(); it != v.end(); ++it) {
      out << separator;
      if (v.is_object()) out << Str(it.key()) << ": ";
      WriteInline(out, it.value());
      separator = ", ";
    }
    out << (v.is_object() ? '}' : ']');
  } else if (v.is_number_float()) {
    const double x = v.get<double>();
    out << (std::isfinite(x) ? Format("%.10g", x) : "null");
  } else if (v.is_string()) {
    out << Str(v.get<std::string>());
  } else {
    out << v.dump();  // integers, booleans, null
  }
}

// The document: one top-level member per line, each written by WriteInline.
void WriteDocument(std::ostream& out, const Json& doc) {
  out << "{\n";
  const char* separator = "";
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    out << separator << "  " << Str(it.key()) << ": ";
    WriteInline(out, it.value());
    separator = ",\n";
  }
  out << "\n}\n";
}

// Statistics over no value are null, not 0.
Json StatsJson(const ErrorStats& s) {
  const auto v = [&s](double x) { return s.count ? Json(x) : Json(nullptr); };
  return {{"count", s.count}, {"rmse", v(s.rmse)}, {"mean", v(s.mean)}, {"median", v(s.median)},
          {"std", v(s.std)},  {"min", v(s.min)},   {"max", v(s.max)}};
}

struct Input {
  std::string path;
  std::string times;
  LoadedTrajectory trajectory;
};

Input Load(const std::string& which, const std::string& path, const std::string& format,
           const std::string& times, bool times_is_shared) {
  if (path.empty()) throw std::invalid_argument("no " + which + " file given");
  std::optional<TrajectoryFormat> f;
  if (!format.empty()) f = ParseFormatName(format);
  const TrajectoryFormat actual = f ? *f : DetectFormat(path);
  Input in;
  in.path = path;
  // A shared --times applies to whichever trajectory is KITTI; a per-file one must fit.
  if (!times.empty() && (actual == TrajectoryFormat::kKitti || !times_is_shared)) {
    in.times = times;
  }
  in.trajectory = ReadTrajectory(path, actual, in.times);
  return in;
}

std::string Describe(const Input& in) {
  const LoadedTrajectory& t = in.trajectory;
  std::string s =
      std::string(FormatName(t.format)) + ", " + std::to_string(t.poses.size()) + " poses";
  if (t.indexed) s += ", no times (associated by index)";
  if (!in.times.empty()) s += ", times from " + in.times;
  if (t.converted_from_ns) s += ", ns times converted to s";
  return s;
}

void Row(std::ostream& out, const std::string& name, const std::string& value,
         const std::string& unit) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), "  %-38s %12s  %s\n", name.c_str(), value.c_str(), unit.c_str());
  out << buf;
}

// What `eval` prints, computed once for either layout.
struct Evaluation {
  EvaluationOptions options;
  Input gt, est;
  Association association;
  TrajectoryEvaluation metrics;
};

// The metric options from --align and --delta/--delta-unit (and the --max-dt check),
// each failure naming its option.
EvaluationOptions ParseOptions(const EvalArgs& args) {
  EvaluationOptions options;
  options.align = ParseAlignmentMode(args.align);
  if (!(std::isfinite(args.max_dt_s) && args.max_dt_s >= 0.0)) {
    throw std::invalid_argument("--max-dt must be >= 0 s");
  }
  options.rpe.delta = args.delta;
  if (args.delta_unit == "frames" || args.delta_unit == "f") {
    options.rpe.unit = DeltaUnit::kFrames;
  } else if (args.delta_unit == "m" || args.delta_unit == "meters") {
    options.rpe.unit = DeltaUnit::kMeters;
  } else {
    throw std::invalid_argument("unknown --delta-unit '" + args.delta_unit +
                                "' (expected frames or m)");
  }
  try {
    options.Validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--delta: ") + e.what());
  }
  return options;
}

Evaluation Evaluate(const EvalArgs& args) {
  Evaluation r;
  r.options = ParseOptions(args);
  // Per-file --gt-times/--est-times must fit their file; the shared --times goes to
  // whichever file is KITTI.
  r.gt = Load("ground-truth", args.gt_path, args.gt_format.empty() ? args.format : args.gt_format,
              args.gt_times.empty() ? args.times : args.gt_times, args.gt_times.empty());
  r.est = Load("estimate", args.est_path, args.est_format.empty() ? args.format : args.est_format,
               args.est_times.empty() ? args.times : args.est_times, args.est_times.empty());
  if (!args.times.empty() && r.gt.times.empty() && r.est.times.empty()) {
    throw std::invalid_argument("--times " + args.times + " applies to KITTI files, but " +
                                "neither " + args.gt_path + " nor " + args.est_path + " is KITTI");
  }

  r.association = Associate(r.gt.trajectory, r.est.trajectory, args.max_dt_s, args.offset_s);
  const Association& a = r.association;
  if (a.gt.size() < 2) {
    std::ostringstream why;
    why << "only " << a.gt.size() << " associated pose pair(s) between " << args.gt_path << " and "
        << args.est_path;
    if (!a.by_index) {
      why << " (max time difference " << args.max_dt_s << " s";
      if (args.offset_s != 0.0) why << ", offset " << args.offset_s << " s";
      why << "; are the times in the same clock and unit?)";
    }
    throw std::runtime_error(why.str());
  }
  r.metrics = EvaluateTrajectory(a.gt, a.est, r.options);
  return r;
}

Json FileJson(const Input& in) {
  return {{"path", in.path},
          {"format", FormatName(in.trajectory.format)},
          {"poses", in.trajectory.poses.size()},
          {"indexed", in.trajectory.indexed}};
}

// The `--json` document; members in the order scripts have always read them.
Json EvalJson(const EvalArgs& args, const Evaluation& r) {
  const TrajectoryEvaluation& e = r.metrics;
  const SimilarityTransform& T = e.ate.alignment.T_gt_est;
  Json R = Json::array();
  for (int row = 0; row < 3; ++row) {
    R.push_back(Json::array({T.R(row, 0), T.R(row, 1), T.R(row, 2)}));
  }
  Json doc;
  doc["gt"] = FileJson(r.gt);
  doc["est"] = FileJson(r.est);
  doc["association"] = {{"pairs", e.pairs},
                        {"by_index", r.association.by_index},
                        {"max_dt_s", args.max_dt_s},
                        {"offset_s", args.offset_s}};
  doc["alignment"] = {{"mode", AlignmentModeName(r.options.align)},
                      {"scale", T.scale},
                      {"unique", e.ate.alignment.unique},
                      {"R", R},
                      {"t", Json::array({T.t.x(), T.t.y(), T.t.z()})}};
  doc["gt_path_length_m"] = e.gt_path_length_m;
  doc["est_path_length_m"] = e.est_path_length_m;
  doc["ate_aligned_m"] = StatsJson(e.ate.error_m);
  doc["ate_rmse_m"] = e.ate_rmse_m;
  doc["rpe"] = {{"delta", r.options.rpe.delta},
                {"delta_unit", r.options.rpe.unit == DeltaUnit::kFrames ? "frames" : "m"},
                {"trans_m", StatsJson(e.rpe.trans_m)},
                {"rot_deg", StatsJson(e.rpe.rot_deg)}};
  // KITTI's segments start at 100 m: null on shorter ground truth.
  doc["kitti"] = e.kitti.segments == 0 ? Json(nullptr)
                                       : Json{{"segments", e.kitti.segments},
                                              {"t_rel_pct", e.kitti.t_rel_pct},
                                              {"r_rel_deg_per_100m", e.kitti.r_rel_deg_per_100m}};
  doc["rpe_trans_pct"] = e.rpe_trans_pct ? Json(*e.rpe_trans_pct) : Json(nullptr);
  doc["final_error_m"] = e.final_error.horizontal_m;
  doc["final_error_pct"] = e.final_error.pct;
  doc["final_error_3d_m"] = e.final_error.error_3d_m;
  doc["final_error_aligned_m"] = e.final_error_aligned_m;
  return doc;
}

void WriteTable(const EvalArgs& args, const Evaluation& r, std::ostream& out) {
  const Input &gt = r.gt, &est = r.est;
  const Association& a = r.association;
  const TrajectoryEvaluation& e = r.metrics;
  const EvaluationOptions& options = r.options;
  const AlignmentMode align = options.align;
  const SimilarityTransform& T = e.ate.alignment.T_gt_est;
  const std::string align_name = AlignmentModeName(align);
  const std::string delta_text =
      Format("%g", options.rpe.delta) + (options.rpe.unit == DeltaUnit::kFrames
                                             ? (options.rpe.delta == 1 ? " frame" : " frames")
                                             : " m");
  const bool has_kitti = e.kitti.segments > 0;

  out << "ground truth  " << gt.path << " (" << Describe(gt) << ")\n";
  out << "estimate      " << est.path << " (" << Describe(est) << ")\n";
  out << "association   " << e.pairs << " pairs of " << gt.trajectory.poses.size() << " / "
      << est.trajectory.poses.size() << " poses "
      << (a.by_index
              ? std::string("by index") +
                    (gt.trajectory.indexed && est.trajectory.indexed ? ""
                     : gt.trajectory.indexed ? " (GT has no times: give --gt-times to use them)"
                                             : " (EST has no times: give --est-times to use them)")
              : "by timestamp (max dt " + Format("%g", args.max_dt_s) + " s" +
                    (args.offset_s != 0.0 ? ", offset " + Format("%g", args.offset_s) + " s" : "") +
                    ")")
      << "\n";
  out << "alignment     " << align_name;
  if (align != AlignmentMode::kNone) {
    out << " (Horn, on positions)"
        << (align == AlignmentMode::kSim3 ? ", scale " + Format("%.6f", T.scale) : "");
    if (!e.ate.alignment.unique) out << "; positions collinear: rotation about the line arbitrary";
  }
  out << "\n";
  out << "path length   ground truth " << Format("%.3f", e.gt_path_length_m) << " m, estimate "
      << Format("%.3f", e.est_path_length_m) << " m\n\n";

  const std::string ate_name =
      "ATE RMSE (3-D, " + align_name + (align == AlignmentMode::kNone ? ")" : "-aligned)");
  Row(out, ate_name, Format("%.4f", e.ate.error_m.rmse), "m");
  out << "    (mean " << Format("%.4f", e.ate.error_m.mean) << ", median "
      << Format("%.4f", e.ate.error_m.median) << ", max " << Format("%.4f", e.ate.error_m.max)
      << " m)\n";
  Row(out, "ATE RMSE (x-y, unaligned)", Format("%.4f", e.ate_rmse_m), "m");
  if (e.rpe.trans_m.count > 0) {
    Row(out, "RPE trans RMSE (delta " + delta_text + ")", Format("%.4f", e.rpe.trans_m.rmse),
        "m (" + std::to_string(e.rpe.trans_m.count) + " pairs)");
    Row(out, "RPE rot RMSE (delta " + delta_text + ")", Format("%.4f", e.rpe.rot_deg.rmse), "deg");
  } else {
    Row(out, "RPE (delta " + delta_text + ")", "n/a", "(no pair of poses that far apart)");
  }
  if (has_kitti) {
    Row(out, "KITTI t_rel (100..800 m)", Format("%.3f", e.kitti.t_rel_pct),
        "% (" + std::to_string(e.kitti.segments) + " segments)");
    Row(out, "KITTI r_rel (100..800 m)", Format("%.3f", e.kitti.r_rel_deg_per_100m), "deg/100 m");
  } else {
    Row(out, "KITTI t_rel / r_rel", "n/a",
        "(ground-truth path " + Format("%.1f", e.gt_path_length_m) + " m: needs > 100 m)");
  }
  if (e.rpe_trans_pct) {
    Row(out, "drift over 10 m (rpe_trans_pct)", Format("%.3f", *e.rpe_trans_pct), "%");
  } else {
    Row(out, "drift over 10 m (rpe_trans_pct)", "n/a", "(path < 10 m)");
  }
  Row(out, "final error (x-y, unaligned)", Format("%.4f", e.final_error.horizontal_m),
      std::isfinite(e.final_error.pct)
          ? "m (" + Format("%.3f", e.final_error.pct) + " % of the path)"
          : "m (% of the path n/a: path < " + Format("%g", kMinPathForPerDistanceM) + " m)");
  if (align != AlignmentMode::kNone) {
    Row(out, "final error (3-D, " + align_name + "-aligned)",
        Format("%.4f", e.final_error_aligned_m), "m");
  }
}

}  // namespace

void RunEval(const EvalArgs& args, std::ostream& out) {
  const Evaluation r = Evaluate(args);
  if (args.json) {
    WriteDocument(out, EvalJson(args, r));
  } else {
    WriteTable(args, r, out);
  }
}

void AddEvalCommand(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  CLI::App* eval = app.add_subcommand(
      "eval",
      "Trajectory metrics of an estimate against ground truth, like evo and the KITTI devkit: "
      "ATE RMSE (aligned), horizontal unaligned ATE, RPE, KITTI t_rel / r_rel, final error");
  eval->add_option("gt", args->gt_path, "Ground-truth trajectory (TUM, KITTI or EuRoC csv)")
      ->required();
  eval->add_option("est", args->est_path, "Estimated trajectory (TUM, KITTI or EuRoC csv)")
      ->required();
  eval->add_option("--format", args->format,
                   "Format of both files: tum|kitti|euroc (default: detected from the content)");
  eval->add_option("--gt-format", args->gt_format, "Format of GT (overrides --format)");
  eval->add_option("--est-format", args->est_format, "Format of EST (overrides --format)");
  eval->add_option("--times", args->times,
                   "Times file (one time [s] per line) for the KITTI file(s); without one, "
                   "KITTI poses are associated by index");
  eval->add_option("--gt-times", args->gt_times, "Times file for GT (KITTI)");
  eval->add_option("--est-times", args->est_times, "Times file for EST (KITTI)");
  eval->add_option("--align", args->align,
                   "Alignment before the ATE: se3|sim3|none (sim3 for monocular estimates)")
      ->capture_default_str();
  eval->add_option("--max-dt", args->max_dt_s,
                   "Largest time difference [s] of associated poses (TUM associate.py: 0.02)")
      ->capture_default_str();
  eval->add_option("--t-offset", args->offset_s, "Offset [s] added to EST's times")
      ->capture_default_str();
  eval->add_option("--delta", args->delta, "RPE pair spacing")->capture_default_str();
  eval->add_option("--delta-unit", args->delta_unit, "RPE spacing unit: frames|m")
      ->capture_default_str();
  eval->add_flag("--json", args->json, "Print JSON instead of the table");
  eval->callback([args]() { RunCommand("eval", [&] { RunEval(*args, std::cout); }); });
}

}  // namespace trackbed::apps
