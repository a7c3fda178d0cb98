// `trackbed eval` (see eval_command.h).
#include "eval_command.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "trackbed/estimation/trajectory_io.h"
#include "trackbed/estimation/trajectory_metrics.h"

namespace trackbed::apps {

namespace {

using namespace trackbed::estimation;

std::string Format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), fmt, v);
  return buf;
}

// A JSON number (finite by construction; null otherwise).
std::string Num(double v) { return std::isfinite(v) ? Format("%.10g", v) : "null"; }

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

std::string StatsJson(const ErrorStats& s) {
  std::ostringstream o;
  o << "{\"count\": " << s.count << ", \"rmse\": " << Num(s.rmse) << ", \"mean\": " << Num(s.mean)
    << ", \"median\": " << Num(s.median) << ", \"std\": " << Num(s.std)
    << ", \"min\": " << Num(s.min) << ", \"max\": " << Num(s.max) << "}";
  return o.str();
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

}  // namespace

void RunEval(const EvalArgs& args, std::ostream& out) {
  const AlignmentMode align = ParseAlignmentMode(args.align);
  if (!(std::isfinite(args.max_dt_s) && args.max_dt_s >= 0.0)) {
    throw std::invalid_argument("--max-dt must be >= 0 s");
  }
  EvaluationOptions options;
  options.align = align;
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

  // Per-file --gt-times/--est-times must fit their file; the shared --times goes to
  // whichever file is KITTI.
  const Input gt =
      Load("ground-truth", args.gt_path, args.gt_format.empty() ? args.format : args.gt_format,
           args.gt_times.empty() ? args.times : args.gt_times, args.gt_times.empty());
  const Input est =
      Load("estimate", args.est_path, args.est_format.empty() ? args.format : args.est_format,
           args.est_times.empty() ? args.times : args.est_times, args.est_times.empty());
  if (!args.times.empty() && gt.times.empty() && est.times.empty()) {
    throw std::invalid_argument("--times " + args.times + " applies to KITTI files, but " +
                                "neither " + args.gt_path + " nor " + args.est_path + " is KITTI");
  }

  const Association a = Associate(gt.trajectory, est.trajectory, args.max_dt_s, args.offset_s);
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
  const TrajectoryEvaluation e = EvaluateTrajectory(a.gt, a.est, options);
  const SimilarityTransform& T = e.ate.alignment.T_gt_est;
  const std::string align_name = AlignmentModeName(align);
  const std::string delta_text =
      Format("%g", options.rpe.delta) + (options.rpe.unit == DeltaUnit::kFrames
                                             ? (options.rpe.delta == 1 ? " frame" : " frames")
                                             : " m");
  const bool has_kitti = e.kitti.segments > 0;

  if (args.json) {
    out << "{\n";
    out << "  \"gt\": {\"path\": " << Str(gt.path)
        << ", \"format\": " << Str(FormatName(gt.trajectory.format))
        << ", \"poses\": " << gt.trajectory.poses.size()
        << ", \"indexed\": " << (gt.trajectory.indexed ? "true" : "false") << "},\n";
    out << "  \"est\": {\"path\": " << Str(est.path)
        << ", \"format\": " << Str(FormatName(est.trajectory.format))
        << ", \"poses\": " << est.trajectory.poses.size()
        << ", \"indexed\": " << (est.trajectory.indexed ? "true" : "false") << "},\n";
    out << "  \"association\": {\"pairs\": " << e.pairs
        << ", \"by_index\": " << (a.by_index ? "true" : "false")
        << ", \"max_dt_s\": " << Num(args.max_dt_s) << ", \"offset_s\": " << Num(args.offset_s)
        << "},\n";
    out << "  \"alignment\": {\"mode\": " << Str(align_name) << ", \"scale\": " << Num(T.scale)
        << ", \"unique\": " << (e.ate.alignment.unique ? "true" : "false") << ", \"R\": [";
    for (int r = 0; r < 3; ++r) {
      out << (r ? ", " : "") << "[" << Num(T.R(r, 0)) << ", " << Num(T.R(r, 1)) << ", "
          << Num(T.R(r, 2)) << "]";
    }
    out << "], \"t\": [" << Num(T.t.x()) << ", " << Num(T.t.y()) << ", " << Num(T.t.z()) << "]},\n";
    out << "  \"gt_path_length_m\": " << Num(e.gt_path_length_m) << ",\n";
    out << "  \"est_path_length_m\": " << Num(e.est_path_length_m) << ",\n";
    out << "  \"ate_aligned_m\": " << StatsJson(e.ate.error_m) << ",\n";
    out << "  \"ate_rmse_m\": " << Num(e.ate_rmse_m) << ",\n";
    out << "  \"rpe\": {\"delta\": " << Num(options.rpe.delta)
        << ", \"delta_unit\": " << Str(options.rpe.unit == DeltaUnit::kFrames ? "frames" : "m")
        << ", \"trans_m\": " << StatsJson(e.rpe.trans_m)
        << ", \"rot_deg\": " << StatsJson(e.rpe.rot_deg) << "},\n";
    out << "  \"kitti\": ";
    if (has_kitti) {
      out << "{\"segments\": " << e.kitti.segments << ", \"t_rel_pct\": " << Num(e.kitti.t_rel_pct)
          << ", \"r_rel_deg_per_100m\": " << Num(e.kitti.r_rel_deg_per_100m) << "},\n";
    } else {
      out << "null,\n";
    }
    out << "  \"rpe_trans_pct\": " << (e.rpe_trans_pct ? Num(*e.rpe_trans_pct) : "null") << ",\n";
    out << "  \"final_error_m\": " << Num(e.final_error.horizontal_m) << ",\n";
    out << "  \"final_error_pct\": " << Num(e.final_error.pct) << ",\n";
    out << "  \"final_error_3d_m\": " << Num(e.final_error.error_3d_m) << ",\n";
    out << "  \"final_error_aligned_m\": " << Num(e.final_error_aligned_m) << "\n";
    out << "}\n";
    return;
  }

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
  Row(out, "RPE trans RMSE (delta " + delta_text + ")", Format("%.4f", e.rpe.trans_m.rmse),
      "m (" + std::to_string(e.rpe.trans_m.count) + " pairs)");
  Row(out, "RPE rot RMSE (delta " + delta_text + ")", Format("%.4f", e.rpe.rot_deg.rmse), "deg");
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
      "m (" + Format("%.3f", e.final_error.pct) + " % of the path)");
  if (align != AlignmentMode::kNone) {
    Row(out, "final error (3-D, " + align_name + "-aligned)",
        Format("%.4f", e.final_error_aligned_m), "m");
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
  eval->callback([args]() {
    try {
      RunEval(*args, std::cout);
      std::cout.flush();
    } catch (const std::exception& e) {
      std::cout.flush();
      std::cerr << "trackbed eval: " << e.what() << std::endl;
      throw CLI::RuntimeError(2);
    }
    throw CLI::RuntimeError(0);
  });
}

}  // namespace trackbed::apps
