// Sparse ZNCC block matching along rectified rows (see stereo_matcher.h).
#include "trackbed/perception/stereo_matcher.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "trackbed/common/option_error.h"

namespace trackbed::perception {
namespace {

/// Bilinear weights of one fractional offset, shared by every sample of a patch whose
/// samples lie at integer steps from one sub-pixel point.
struct Bilinear {
  float w00, w01, w10, w11;  // (row, col): (y0, x0), (y0, x0+1), (y0+1, x0), (y0+1, x0+1)
  Bilinear(float fx, float fy)
      : w00((1.0f - fx) * (1.0f - fy)),
        w01(fx * (1.0f - fy)),
        w10((1.0f - fx) * fy),
        w11(fx * fy) {}
};

/// Samples `rows` x `cols` values of `image` starting at integer (x0, y0) with the
/// bilinear weights `b` (offsets in [0, 1) to the right and down) into `out`
/// (row-major). Reads column x0 + cols and row y0 + rows only through their weight,
/// clamped to the image, so a zero fraction at the last column is safe.
void SamplePatch(const cv::Mat& image, int x0, int y0, int cols, int rows, const Bilinear& b,
                 float* out) {
  const int last_row = image.rows - 1;
  const int last_col = image.cols - 1;
  for (int j = 0; j < rows; ++j) {
    const unsigned char* r0 = image.ptr<unsigned char>(std::min(y0 + j, last_row));
    const unsigned char* r1 = image.ptr<unsigned char>(std::min(y0 + j + 1, last_row));
    float* o = out + static_cast<std::ptrdiff_t>(j) * cols;
    const int safe_cols = std::min(cols, last_col - x0);  // x + 1 <= last_col
    int i = 0;
    for (; i < safe_cols; ++i) {
      const int x = x0 + i;
      o[i] = b.w00 * r0[x] + b.w01 * r0[x + 1] + b.w10 * r1[x] + b.w11 * r1[x + 1];
    }
    for (; i < cols; ++i) {
      const int x = std::min(x0 + i, last_col);
      const int x1 = std::min(x + 1, last_col);
      o[i] = b.w00 * r0[x] + b.w01 * r0[x1] + b.w10 * r1[x] + b.w11 * r1[x1];
    }
  }
}

void CheckPair(const cv::Mat& left, const cv::Mat& right) {
  if (left.empty() || right.empty() || left.type() != CV_8UC1 || right.type() != CV_8UC1 ||
      left.size() != right.size()) {
    throw std::invalid_argument(
        "StereoMatcher::Match: needs two non-empty CV_8UC1 images of one size");
  }
}

/// Uniqueness compares costs 1 − ZNCC, floored here (ZNCC 0.99 ≈ image noise).
constexpr double kCostFloor = 0.01;

}  // namespace

void StereoMatcherOptions::Validate() const {
  if (window_px < 3 || window_px % 2 == 0) {
    throw OptionError("window_px", "must be odd and >= 3 (got " + std::to_string(window_px) + ")");
  }
  if (min_disparity_px < 0) {
    throw OptionError("min_disparity_px",
                      "must be >= 0 (got " + std::to_string(min_disparity_px) + ")");
  }
  if (max_disparity_px < min_disparity_px + 2) {
    throw OptionError("max_disparity_px", "must be >= min_disparity_px + 2 (got " +
                                              std::to_string(max_disparity_px) + ")");
  }
  option_check::InRange("min_zncc", min_zncc, -1.0, 1.0);
  option_check::NonNegative("uniqueness_ratio", uniqueness_ratio);
  option_check::NonNegative("max_left_right_px", max_left_right_px);
  option_check::NonNegative("min_texture", min_texture);
  if (refinement_iterations < 0) {
    throw OptionError("refinement_iterations",
                      "must be >= 0 (got " + std::to_string(refinement_iterations) + ")");
  }
}

const char* ToString(StereoMatchStatus status) {
  switch (status) {
    case StereoMatchStatus::kMatched:
      return "matched";
    case StereoMatchStatus::kOutOfImage:
      return "out_of_image";
    case StereoMatchStatus::kLowTexture:
      return "low_texture";
    case StereoMatchStatus::kWeak:
      return "weak";
    case StereoMatchStatus::kAtRangeLimit:
      return "at_range_limit";
    case StereoMatchStatus::kAmbiguous:
      return "ambiguous";
    case StereoMatchStatus::kLeftRightMismatch:
      return "left_right_mismatch";
  }
  return "unknown";
}

StereoMatcher::StereoMatcher(const StereoMatcherOptions& options) : options_(options) {
  options_.Validate();
}

namespace {

/// The candidate with the highest score (the first of equals).
int BestCandidate(const float* scores, int candidates) {
  int best = 0;
  for (int k = 1; k < candidates; ++k) {
    if (scores[k] > scores[best]) best = k;
  }
  return best;
}

/// The best local maximum other than the peak at `best` and its two neighbours (which
/// are the peak's own flanks, not a rival match); −1 when there is none.
float SecondLocalMaximum(const float* scores, int candidates, int best) {
  float second = -1.0f;
  for (int k = 0; k < candidates; ++k) {
    if (k >= best - 1 && k <= best + 1) continue;
    const bool left_ok = k == 0 || scores[k] >= scores[k - 1];
    const bool right_ok = k == candidates - 1 || scores[k] >= scores[k + 1];
    if (left_ok && right_ok) second = std::max(second, scores[k]);
  }
  return second;
}

/// Whether the peak at `best` is a match: kWeak below min_zncc, kAmbiguous when another
/// local maximum is nearly as good, kAtRangeLimit at either end of the range (the true
/// peak may lie beyond it), else kMatched.
StereoMatchStatus PeakStatus(const StereoMatcherOptions& options, const float* scores,
                             int candidates, int best) {
  if (!(scores[best] >= options.min_zncc)) return StereoMatchStatus::kWeak;
  const float second = SecondLocalMaximum(scores, candidates, best);
  // Costs below the floor are equally perfect: otherwise a repeated pattern whose copies
  // all match almost exactly (cost 1e-6 vs 3e-6) would pass as unique.
  const double cost_best = std::max(1.0 - scores[best], kCostFloor);
  const double cost_second = std::max(1.0 - second, kCostFloor);
  if (cost_second < (1.0 + options.uniqueness_ratio) * cost_best) {
    return StereoMatchStatus::kAmbiguous;
  }
  if (best == 0 || best == candidates - 1) return StereoMatchStatus::kAtRangeLimit;
  return StereoMatchStatus::kMatched;
}

/// Sub-candidate offset of the peak at `best` (not at either end): the vertex of the
/// parabola through the scores at best−1, best, best+1, within ±0.5.
float ParabolaOffset(const float* scores, int best) {
  const float a = scores[best - 1], c = scores[best + 1], peak = scores[best];
  const float curvature = a - 2.0f * peak + c;
  return curvature < 0.0f ? std::clamp(0.5f * (a - c) / curvature, -0.5f, 0.5f) : 0.0f;
}

}  // namespace

bool StereoMatcher::PlanRowWindow(const cv::Mat& ref, const cv::Mat& other, float u, float v,
                                  int sign, RowWindow* window) const {
  const int w = options_.window_px;
  const int h = w / 2;
  const float last_x = static_cast<float>(ref.cols - 1);
  const float last_y = static_cast<float>(ref.rows - 1);
  if (!(u - static_cast<float>(h) >= 0.0f && u + static_cast<float>(h) <= last_x &&
        v - static_cast<float>(h) >= 0.0f && v + static_cast<float>(h) <= last_y)) {
    return false;
  }
  const float ux = std::floor(u), vy = std::floor(v);
  const int x0 = static_cast<int>(ux) - h;  // first column of the reference window
  window->x0 = x0;
  window->y0 = static_cast<int>(vy) - h;
  window->fx = u - ux;
  window->fy = v - vy;

  // Disparities whose window lies inside `other`: columns x0 + sign·d … x0 + sign·d + w−1
  // (+1 for the bilinear neighbour when the fraction is non-zero).
  const int extra = (u > ux) ? 1 : 0;
  int d_lo = options_.min_disparity_px, d_hi = options_.max_disparity_px;
  if (sign < 0) {
    d_hi = std::min(d_hi, x0);                                     // x0 − d >= 0
    d_lo = std::max(d_lo, x0 + w - 1 + extra - (other.cols - 1));  // right end inside
  } else {
    d_hi = std::min(d_hi, other.cols - 1 - (x0 + w - 1 + extra));  // right end inside
    d_lo = std::max(d_lo, -x0);                                    // x0 + d >= 0
  }
  window->d_lo = d_lo;
  window->d_hi = d_hi;
  // Fewer than 3 candidates leave no peak with two neighbours to test or refine.
  return d_hi - d_lo + 1 >= 3;
}

bool StereoMatcher::SampleReferencePatch(const cv::Mat& ref, const RowWindow& window,
                                         double* patch_norm) {
  const int w = options_.window_px;
  const int n = w * w;
  patch_.resize(static_cast<std::size_t>(n));
  SamplePatch(ref, window.x0, window.y0, w, w, Bilinear(window.fx, window.fy), patch_.data());
  double mean = 0.0;
  for (float p : patch_) mean += p;
  mean /= n;
  double ss = 0.0;
  for (float& p : patch_) {
    p = static_cast<float>(p - mean);
    ss += static_cast<double>(p) * p;
  }
  if (!(std::sqrt(ss / n) >= options_.min_texture) || ss <= 0.0) return false;
  *patch_norm = std::sqrt(ss);
  return true;
}

void StereoMatcher::ScoreCandidates(const cv::Mat& other, const RowWindow& window, int sign,
                                    double patch_norm) {
  // Strip of `other`: w rows, nd − 1 + w columns; candidate k's window starts at strip
  // column k. For sign < 0 (left → right) column k is disparity d_hi − k, for sign > 0
  // (right → left) d_lo + k.
  const int w = options_.window_px;
  const int nd = window.candidates();
  const int strip_cols = nd - 1 + w;
  const int strip_x0 = sign < 0 ? window.x0 - window.d_hi : window.x0 + window.d_lo;
  strip_.resize(static_cast<std::size_t>(strip_cols) * static_cast<std::size_t>(w));
  SamplePatch(other, strip_x0, window.y0, strip_cols, w, Bilinear(window.fx, window.fy),
              strip_.data());
  CrossCorrelateStrip(strip_cols, nd);
  NormaliseToZncc(strip_cols, nd, patch_norm);
}

void StereoMatcher::CrossCorrelateStrip(int strip_cols, int nd) {
  // Cross-correlation with the zero-mean patch: Σ P̃·S = Σ P̃·(S − mean S).
  // Blocks of kBlock candidates whose sums stay in registers over the whole window.
  const int w = options_.window_px;
  constexpr int kBlock = 16;
  scores_.assign(static_cast<std::size_t>(nd), 0.0f);
  float* acc = scores_.data();
  int k0 = 0;
  for (; k0 + kBlock <= nd; k0 += kBlock) {
    using Block = Eigen::Array<float, kBlock, 1>;
    Block block = Block::Zero();
    for (int j = 0; j < w; ++j) {
      const float* srow = strip_.data() + static_cast<std::ptrdiff_t>(j) * strip_cols + k0;
      const float* prow = patch_.data() + static_cast<std::ptrdiff_t>(j) * w;
      for (int i = 0; i < w; ++i) block += prow[i] * Eigen::Map<const Block>(srow + i);
    }
    Eigen::Map<Block>(acc + k0) = block;
  }
  for (int j = 0; j < w; ++j) {  // the remaining candidates
    const float* srow = strip_.data() + static_cast<std::ptrdiff_t>(j) * strip_cols;
    const float* prow = patch_.data() + static_cast<std::ptrdiff_t>(j) * w;
    for (int i = 0; i < w; ++i) {
      for (int k = k0; k < nd; ++k) acc[k] += prow[i] * srow[i + k];
    }
  }
}

void StereoMatcher::NormaliseToZncc(int strip_cols, int nd, double patch_norm) {
  // Window sums of S and S² from column sums, sliding along the strip.
  const int w = options_.window_px;
  const int n = w * w;
  float* acc = scores_.data();
  col_sum_.assign(static_cast<std::size_t>(strip_cols), 0.0f);
  col_sum_sq_.assign(static_cast<std::size_t>(strip_cols), 0.0f);
  for (int j = 0; j < w; ++j) {
    const float* srow = strip_.data() + static_cast<std::ptrdiff_t>(j) * strip_cols;
    for (int t = 0; t < strip_cols; ++t) {
      col_sum_[static_cast<std::size_t>(t)] += srow[t];
      col_sum_sq_[static_cast<std::size_t>(t)] += srow[t] * srow[t];
    }
  }
  double sum = 0.0, sum_sq = 0.0;
  for (int t = 0; t < w; ++t) {
    sum += col_sum_[static_cast<std::size_t>(t)];
    sum_sq += col_sum_sq_[static_cast<std::size_t>(t)];
  }
  for (int k = 0; k < nd; ++k) {
    if (k > 0) {
      sum +=
          col_sum_[static_cast<std::size_t>(k + w - 1)] - col_sum_[static_cast<std::size_t>(k - 1)];
      sum_sq += col_sum_sq_[static_cast<std::size_t>(k + w - 1)] -
                col_sum_sq_[static_cast<std::size_t>(k - 1)];
    }
    const double var = sum_sq - sum * sum / n;  // n × variance of the candidate window
    acc[k] = var > 1e-6 ? static_cast<float>(acc[k] / (patch_norm * std::sqrt(var))) : -1.0f;
  }
}

StereoMatcher::Search StereoMatcher::SearchRow(const cv::Mat& ref, const cv::Mat& other, float u,
                                               float v, int sign, bool refine) {
  Search result;
  RowWindow window;
  if (!PlanRowWindow(ref, other, u, v, sign, &window)) return result;  // kOutOfImage
  double patch_norm = 0.0;
  if (!SampleReferencePatch(ref, window, &patch_norm)) {
    result.status = StereoMatchStatus::kLowTexture;
    return result;
  }
  ScoreCandidates(other, window, sign, patch_norm);

  const int nd = window.candidates();
  const float* scores = scores_.data();
  const int best = BestCandidate(scores, nd);
  result.zncc = scores[best];
  result.status = PeakStatus(options_, scores, nd, best);
  if (result.status != StereoMatchStatus::kMatched) return result;
  const float k_sub = static_cast<float>(best) + ParabolaOffset(scores, best);
  result.disparity =
      sign < 0 ? static_cast<float>(window.d_hi) - k_sub : static_cast<float>(window.d_lo) + k_sub;
  if (refine && options_.refinement_iterations > 0) {
    result.disparity = RefineDisparity(other, u, v, sign, result.disparity);
  }
  return result;
}

namespace {

using Vector5d = Eigen::Matrix<double, 5, 1>;
using Matrix5d = Eigen::Matrix<double, 5, 5>;

/// One window row's sums for RefineDisparity: of q², q²i, q²i², qo, qoi, q, qi, o², o,
/// and of q·e, q·e·i, o·e, e.
struct RowSums {
  float qq = 0, qqi = 0, qqii = 0, qo = 0, qoi = 0, q1 = 0, qi1 = 0, oo = 0, o1 = 0;
  float qe = 0, qei = 0, oe = 0, e1 = 0;
};

/// Adds row j's sums (j constant along the row, `w` samples) to Σ J Jᵀ (upper triangle)
/// and Σ J e with J = (q, q·i, q·j, o, 1).
void AddRow(const RowSums& r, double dj, int w, Matrix5d* H, Vector5d* g) {
  (*H)(0, 0) += r.qq;
  (*H)(0, 1) += r.qqi;
  (*H)(0, 2) += r.qq * dj;
  (*H)(0, 3) += r.qo;
  (*H)(0, 4) += r.q1;
  (*H)(1, 1) += r.qqii;
  (*H)(1, 2) += r.qqi * dj;
  (*H)(1, 3) += r.qoi;
  (*H)(1, 4) += r.qi1;
  (*H)(2, 2) += r.qq * dj * dj;
  (*H)(2, 3) += r.qo * dj;
  (*H)(2, 4) += r.q1 * dj;
  (*H)(3, 3) += r.oo;
  (*H)(3, 4) += r.o1;
  (*H)(4, 4) += w;
  (*g)(0) += r.qe;
  (*g)(1) += r.qei;
  (*g)(2) += r.qe * dj;
  (*g)(3) += r.oe;
  (*g)(4) += r.e1;
}

}  // namespace

float StereoMatcher::RefineDisparity(const cv::Mat& other, float u, float v, int sign, float d0) {
  // Gauss–Newton (Lucas & Kanade 1981, in one dimension) on
  //   e_ij = a·O(u + sign·(d + g_x·i + g_y·j) + i, v + j) + b − P_ij
  // over θ = (d, g_x, g_y, a, b): P is the zero-mean reference patch (patch_), O the other
  // image sampled bilinearly, O_x its derivative by central differences (±1 px), i, j the
  // window offsets. The disparity gradient (g_x, g_y) [px/px] models a slanted surface:
  // a floor seen from height h has g_y = baseline/h (0.3 for KITTI's road), which a
  // constant-disparity window would average unevenly over its rows. Gain and offset are
  // the photometric model ZNCC is invariant to.
  const int w = options_.window_px;
  const int h = w / 2;
  const int n = w * w;
  const float max_x = static_cast<float>(other.cols - 3);  // x − 1 >= 0, x + 2 <= cols − 1
  const float max_y = static_cast<float>(other.rows - 2);
  // Each row interpolated vertically (its y is the same in every iteration) once, in the
  // first iteration, over the columns later ones reach while |d − d0| <= 1 and
  // |g_x|, |g_y| < 0.5 (within 2h + 1 of u + sign·d0, and the taps beside them); a
  // column outside these is interpolated where it is needed.
  const int centre = static_cast<int>(std::floor(u + static_cast<float>(sign) * d0));
  const int lo = std::max(0, centre - 2 * h - 4);
  const int hi = std::min(other.cols - 1, centre + 2 * h + 4);
  const int span = std::max(hi - lo + 1, 0);
  rows_.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(span));
  double d = d0, gx = 0.0, gy = 0.0, a = 1.0, b = 0.0;
  for (int iteration = 0; iteration < options_.refinement_iterations; ++iteration) {
    double so = 0.0, soo = 0.0, sop = 0.0;  // Σo, Σo², Σo·P (first pass: gain/offset)
    Matrix5d H = Matrix5d::Zero();
    Vector5d g = Vector5d::Zero();
    for (int j = -h; j <= h; ++j) {
      const float y = v + static_cast<float>(j);
      if (!(y >= 0.0f && y <= max_y)) return d0;
      const int y0 = static_cast<int>(y);
      const float fy = y - static_cast<float>(y0);
      const unsigned char* r0 = other.ptr<unsigned char>(y0);
      const unsigned char* r1 = other.ptr<unsigned char>(y0 + 1);
      const auto at = [&](int x) {  // the row interpolated vertically at column x
        return (1.0f - fy) * static_cast<float>(r0[x]) + fy * static_cast<float>(r1[x]);
      };
      float* row = rows_.data() + static_cast<std::ptrdiff_t>(j + h) * span;
      if (iteration == 0) {
        for (int x = lo; x <= hi; ++x) row[x - lo] = at(x);
      }
      const float* prow = patch_.data() + static_cast<std::ptrdiff_t>(j + h) * w;
      const double base = u + sign * (d + gy * j);
      const double slope = 1.0 + sign * gx;
      RowSums r;
      for (int i = -h; i <= h; ++i) {
        const float x = static_cast<float>(base + slope * i);
        if (!(x >= 1.0f && x <= max_x)) return d0;
        const int x0 = static_cast<int>(x);
        const float fx = x - static_cast<float>(x0);
        float cm, c0, c1, c2;
        if (x0 - 1 >= lo && x0 + 2 <= hi) {
          const float* c = row + (x0 - lo);
          cm = c[-1], c0 = c[0], c1 = c[1], c2 = c[2];
        } else {
          cm = at(x0 - 1), c0 = at(x0), c1 = at(x0 + 1), c2 = at(x0 + 2);
        }
        const float o = c0 + fx * (c1 - c0);
        const float p = prow[i + h];
        if (iteration == 0) {
          so += o;
          soo += static_cast<double>(o) * o;
          sop += static_cast<double>(o) * p;
          continue;
        }
        // O_x = (O(x + 1) − O(x − 1)) / 2, each bilinear.
        const float ox = 0.5f * ((c1 + fx * (c2 - c1)) - (cm + fx * (c0 - cm)));
        const float q = static_cast<float>(a * sign) * ox;
        const float e = static_cast<float>(a) * o + static_cast<float>(b) - p;
        const float fi = static_cast<float>(i);
        r.qq += q * q;
        r.qqi += q * q * fi;
        r.qqii += q * q * fi * fi;
        r.qo += q * o;
        r.qoi += q * o * fi;
        r.q1 += q;
        r.qi1 += q * fi;
        r.oo += o * o;
        r.o1 += o;
        r.qe += q * e;
        r.qei += q * e * fi;
        r.oe += o * e;
        r.e1 += e;
      }
      if (iteration > 0) AddRow(r, j, w, &H, &g);
    }
    if (iteration == 0) {
      // Gain and offset start at the least-squares fit of the values (Σ P = 0).
      const double var = soo - so * so / n;
      if (!(var > 1e-6)) return d0;
      a = sop / var;
      b = -a * so / n;
      continue;
    }
    const Vector5d step = H.selfadjointView<Eigen::Upper>().ldlt().solve(-g);
    if (!step.allFinite()) return d0;
    d += step(0);
    gx += step(1);
    gy += step(2);
    a += step(3);
    b += step(4);
    if (!(std::abs(d - d0) <= 1.0 && std::abs(gx) < 0.5 && std::abs(gy) < 0.5)) return d0;
    if (std::abs(step(0)) < 0.005) break;
  }
  return static_cast<float>(d);
}

StereoMatch StereoMatcher::MatchOne(const cv::Mat& left, const cv::Mat& right,
                                    const cv::Point2f& point) {
  StereoMatch match;
  const Search forward = SearchRow(left, right, point.x, point.y, -1, /*refine=*/true);
  match.zncc = forward.zncc;
  match.status = forward.status;
  if (forward.status != StereoMatchStatus::kMatched) return match;
  match.disparity_px = forward.disparity;
  if (options_.max_left_right_px > 0.0) {
    // The consistency check needs no sub-pixel refinement (its tolerance is ~1 px).
    const Search backward =
        SearchRow(right, left, point.x - forward.disparity, point.y, +1, /*refine=*/false);
    if (backward.status != StereoMatchStatus::kMatched ||
        !(std::abs(backward.disparity - forward.disparity) <= options_.max_left_right_px)) {
      match.status = StereoMatchStatus::kLeftRightMismatch;
    }
  }
  return match;
}

int StereoMatcher::Match(const cv::Mat& left, const cv::Mat& right,
                         const std::vector<cv::Point2f>& points,
                         std::vector<StereoMatch>* matches) {
  CheckPair(left, right);
  matches->resize(points.size());
  int valid = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    (*matches)[i] = MatchOne(left, right, points[i]);
    if ((*matches)[i].valid()) ++valid;
  }
  return valid;
}

StereoMatch StereoMatcher::Match(const cv::Mat& left, const cv::Mat& right,
                                 const cv::Point2f& point) {
  CheckPair(left, right);
  return MatchOne(left, right, point);
}

}  // namespace trackbed::perception
