// The heading a resting IMU's gyro alone integrates to over the kilometre loop's 2670 s
// (seeds 1–20), per realism profile's part (robot/imu_parts.h): its spread (RMS over the
// seeds, the 1σ of a zero-mean error) with the turn-on bias and without it (the in-run
// noise alone), beside what the part's numbers predict: white noise N·√T, a bias random
// walk K·T^1.5/√3, each Gauss–Markov term √(2σ²τ_c²(T/τ_c − 1 + e^{−T/τ_c})), a turn-on
// bias σ₀·T. Also the model's Allan deviation over the part's at τ = 1, 10, 100, 1000 s
// from 30 000 s records, per seed (--allan-seeds). docs/results/2026-12-07-plant-imu.md.
// With --latitude-deg, the `typical` part at rest upright at that latitude
// (scene.geodetic_origin): the heading its gyro integrates to without the Earth's rate,
// with it, and with it less the zero-velocity bias estimate the stack makes at every
// sample (estimation/gyro_bias.h, the robot standing the whole time).
// docs/results/2026-12-07-gazebo-geodetic-and-albedo.md.
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench_args.h"
#include "trackbed/common/units.h"
#include "trackbed/estimation/allan_deviation.h"
#include "trackbed/estimation/gyro_bias.h"
#include "trackbed/robot/imu.h"
#include "trackbed/robot/imu_parts.h"
#include "trackbed/sim/geodetic_origin.h"

namespace trackbed {
namespace {

using robot::ImuOptions;
using robot::Realism;

// The z gyro integrated over `duration_s` at rest [rad].
double IntegratedHeading(const ImuOptions& o, std::uint64_t seed, double duration_s) {
  robot::Imu imu(o, 9.81, seed);
  const double dt = 1.0 / o.rate_hz;
  const auto n = static_cast<long>(std::llround(duration_s / dt));
  double heading = 0.0;
  for (long i = 1; i <= n; ++i) {
    heading += imu.Sample(static_cast<double>(i) * dt, Eigen::Matrix3d::Identity(),
                          Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero())
                   .gyro_radps.z() *
               dt;
  }
  return heading;
}

double RmsOverSeeds(const ImuOptions& o, int seeds, double duration_s) {
  double sum = 0.0;
  for (int s = 1; s <= seeds; ++s) sum += std::pow(IntegratedHeading(o, s, duration_s), 2);
  return std::sqrt(sum / seeds);
}

// What the part's numbers predict for the heading's 1σ after T [rad], in-run only.
double PredictedInRun(const ImuOptions& o, double t) {
  double var = std::pow(*o.gyro_noise_density, 2) * t +
               std::pow(*o.gyro_bias_random_walk, 2) * t * t * t / 3.0;
  for (std::size_t k = 0; k < o.gyro_bias_markov_std->size(); ++k) {
    const double s = (*o.gyro_bias_markov_std)[k], tc = (*o.gyro_bias_markov_tau_s)[k];
    var += 2.0 * s * s * tc * tc * (t / tc - 1.0 + std::exp(-t / tc));
  }
  return std::sqrt(var);
}

void HeadingTable(int seeds, double duration_s) {
  std::printf("heading after %.0f s at rest, seeds 1-%d, 1 sigma [deg]\n", duration_s, seeds);
  std::printf("%-34s %10s %10s %10s %10s %10s\n", "part (profile)", "with t-on", "in-run", "pred N",
              "pred bias", "pred t-on");
  for (const Realism profile : {Realism::kIdeal, Realism::kTypical, Realism::kHarsh}) {
    const robot::ImuPart part = robot::ProfileImuPart(profile);
    const ImuOptions o = robot::WithImuPartResolved(ImuOptions{}, part);
    ImuOptions in_run = o;
    in_run.gyro_initial_bias_std = 0.0;
    ImuOptions white = in_run;
    white.gyro_bias_random_walk = 0.0;
    white.gyro_bias_markov_std->clear();
    white.gyro_bias_markov_tau_s->clear();
    const double t = duration_s;
    const double n = *o.gyro_noise_density * std::sqrt(t);
    const double bias = std::sqrt(std::max(0.0, std::pow(PredictedInRun(o, t), 2) - n * n));
    std::printf("%-34s %10.2f %10.2f %10.2f %10.2f %10.2f\n", part.name.c_str(),
                units::Degrees(RmsOverSeeds(o, seeds, t)),
                units::Degrees(RmsOverSeeds(in_run, seeds, t)), units::Degrees(n),
                units::Degrees(bias), units::Degrees(*o.gyro_initial_bias_std * t));
  }
}

// The headings after `duration_s` at rest [rad]: the raw gyro's, and less the
// zero-velocity bias estimate (encoders at 100 Hz, counts still; standstill window 0.5 s).
struct RestHeadings {
  double raw = 0.0, zero_velocity = 0.0;
};

RestHeadings HeadingsAtRest(const ImuOptions& o, std::uint64_t seed, double duration_s,
                            const Eigen::Vector3d* earth_rate) {
  robot::Imu imu(o, 9.81, seed);
  if (earth_rate != nullptr) imu.SetEarthRate(*earth_rate);
  estimation::GyroModel model;
  model.noise_density = *o.gyro_noise_density;
  model.bias_random_walk = *o.gyro_bias_random_walk;
  model.turn_on_bias_std = *o.gyro_initial_bias_std;
  double markov_var = 0.0;
  for (const double s : *o.gyro_bias_markov_std) markov_var += s * s;
  model.bias_instability_std = std::sqrt(markov_var);
  estimation::ZeroVelocityGyroBias zupt(model, 0.5);
  const double dt = 1.0 / o.rate_hz;
  const auto n = static_cast<long>(std::llround(duration_s / dt));
  const long per_encoder = std::max(1L, std::lround(0.01 / dt));
  RestHeadings h;
  for (long i = 1; i <= n; ++i) {
    const double t = static_cast<double>(i) * dt;
    const double rate =
        imu.Sample(t, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero())
            .gyro_radps.z();
    zupt.AddGyroSample(t, Eigen::Vector3d(0, 0, rate));
    if (i % per_encoder == 0) zupt.AddEncoderSample(t, 0, 0);
    h.raw += rate * dt;
    h.zero_velocity += (rate - zupt.bias().z()) * dt;
  }
  return h;
}

void EarthRateTable(int seeds, double duration_s, double latitude_deg) {
  const robot::ImuPart part = robot::ProfileImuPart(Realism::kTypical);
  const ImuOptions o = robot::WithImuPartResolved(ImuOptions{}, part);
  sim::GeodeticOrigin origin;
  origin.latitude_deg = latitude_deg;
  const Eigen::Vector3d earth = origin.EarthRateInWorld();
  std::printf("%s at rest upright for %.0f s at latitude %.2f deg, seeds 1-%d: heading [deg]\n",
              part.name.c_str(), duration_s, latitude_deg, seeds);
  std::printf("Earth's vertical rate %.4f deg/h: %.3f deg over the run\n",
              units::Degrees(earth.z()) * 3600.0, units::Degrees(earth.z() * duration_s));
  std::printf("%-26s %10s %10s %10s %10s\n", "", "raw mean", "raw RMS", "ZV mean", "ZV RMS");
  for (const bool with_earth : {false, true}) {
    double raw = 0, raw2 = 0, zv = 0, zv2 = 0;
    for (int s = 1; s <= seeds; ++s) {
      const RestHeadings h = HeadingsAtRest(o, s, duration_s, with_earth ? &earth : nullptr);
      raw += h.raw;
      raw2 += h.raw * h.raw;
      zv += h.zero_velocity;
      zv2 += h.zero_velocity * h.zero_velocity;
    }
    std::printf("%-26s %10.3f %10.3f %10.4f %10.4f\n",
                with_earth ? "with the Earth's rate" : "without the Earth's rate",
                units::Degrees(raw / seeds), units::Degrees(std::sqrt(raw2 / seeds)),
                units::Degrees(zv / seeds), units::Degrees(std::sqrt(zv2 / seeds)));
  }
}

void AllanTable(int seeds) {
  const std::vector<double> taus = {1.0, 10.0, 100.0, 1000.0};
  std::printf("Allan deviation, model / part, 30000 s at rest, three axes' variance averaged\n");
  for (const Realism profile : {Realism::kTypical, Realism::kHarsh}) {
    const robot::ImuPart part = robot::ProfileImuPart(profile);
    const ImuOptions o = robot::WithImuPartResolved(ImuOptions{}, part);
    for (int seed = 1; seed <= seeds; ++seed) {
      robot::Imu imu(o, 9.81, seed);
      const double dt = 1.0 / o.rate_hz;
      std::vector<std::vector<double>> theta(6, std::vector<double>(1, 0.0));
      Eigen::Matrix<double, 6, 1> sum = Eigen::Matrix<double, 6, 1>::Zero();
      for (long i = 1; i <= 6000000; ++i) {
        const robot::ImuSample s =
            imu.Sample(static_cast<double>(i) * dt, Eigen::Matrix3d::Identity(),
                       Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
        sum.head<3>() += s.gyro_radps * dt;
        sum.tail<3>() += (s.accel_mps2 - Eigen::Vector3d(0, 0, 9.81)) * dt;
        if (i % 10 == 0) {
          for (int a = 0; a < 6; ++a) theta[a].push_back(sum[a]);
        }
      }
      std::printf("%-10s seed %2d", part.name.c_str(), seed);
      for (const bool gyro : {true, false}) {
        std::vector<double> var(taus.size(), 0.0);
        for (int a = gyro ? 0 : 3; a < (gyro ? 3 : 6); ++a) {
          const std::vector<double> d =
              estimation::OverlappingAllanDeviationOfIntegral(theta[a], 10 * dt, taus);
          for (std::size_t i = 0; i < taus.size(); ++i) var[i] += d[i] * d[i] / 3.0;
        }
        std::printf("  %s", gyro ? "gyro" : "accel");
        for (std::size_t i = 0; i < taus.size(); ++i) {
          const robot::ImuSensorSpec& spec = gyro ? part.gyro : part.accel;
          std::printf(" %.3f", std::sqrt(var[i]) / spec.AllanDeviation(taus[i]));
        }
      }
      std::printf("\n");
    }
  }
}

}  // namespace
}  // namespace trackbed

int main(int argc, char** argv) {
  CLI::App app{
      "Heading drift of a resting IMU's gyro per realism profile, and its Allan deviation"};
  int seeds = 20, allan_seeds = 0;
  double duration_s = 2670.0;
  app.add_option("--seeds", seeds, "Seeds 1..N of the heading table (default 20)");
  app.add_option("--duration", duration_s, "Seconds at rest (default 2670, the kilometre loop)");
  app.add_option("--allan-seeds", allan_seeds,
                 "Also the Allan deviation table for seeds 1..N (default 0: not)");
  double latitude_deg = std::nan("");
  app.add_option("--latitude-deg", latitude_deg,
                 "Instead: the typical part at rest at this latitude, with and without the "
                 "Earth's rate, raw and less the zero-velocity bias estimate");
  if (const auto status = trackbed::bench::Parse(app, argc, argv)) return *status;
  if (!std::isnan(latitude_deg)) {
    trackbed::EarthRateTable(seeds, duration_s, latitude_deg);
    return 0;
  }
  trackbed::HeadingTable(seeds, duration_s);
  if (allan_seeds > 0) trackbed::AllanTable(allan_seeds);
  return 0;
}
