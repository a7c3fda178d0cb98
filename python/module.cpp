// The compiled part of the Python package `trackbed` (docs/python.md): the simulation
// of simulation.h with numpy arrays in and out, and the C++ exceptions as Python's.
// The thin Python layer (trackbed/__init__.py, trackbed/gym.py) builds on it.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "simulation.h"

namespace py = pybind11;

namespace trackbed::python {
namespace {

py::array_t<std::uint8_t> ToArray(const GrayImage& image) {
  py::array_t<std::uint8_t> a({image.height, image.width});
  std::memcpy(a.mutable_data(), image.pixels.data(), image.pixels.size());
  return a;
}

py::array_t<double> ToArray(const Eigen::Matrix4d& T) {
  py::array_t<double> a({4, 4});
  auto m = a.mutable_unchecked<2>();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m(r, c) = T(r, c);
  }
  return a;
}

py::array_t<double> ToArray(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(double));
  return a;
}

// What a step produced, as a dict of numpy arrays (the Python layer's Observation).
py::dict StepDict(const runner::StepResult& r) {
  py::dict d;
  d["t"] = r.t_s;
  py::array_t<double> encoders({static_cast<py::ssize_t>(r.encoders.size()), py::ssize_t{3}});
  auto e = encoders.mutable_unchecked<2>();
  for (std::size_t k = 0; k < r.encoders.size(); ++k) {
    const auto i = static_cast<py::ssize_t>(k);
    e(i, 0) = r.encoders[k].t_s;
    e(i, 1) = static_cast<double>(r.encoders[k].ticks[0]);
    e(i, 2) = static_cast<double>(r.encoders[k].ticks[1]);
  }
  d["encoder_readings"] = encoders;
  py::array_t<double> imu({static_cast<py::ssize_t>(r.imu.size()), py::ssize_t{7}});
  auto m = imu.mutable_unchecked<2>();
  for (std::size_t k = 0; k < r.imu.size(); ++k) {
    const auto i = static_cast<py::ssize_t>(k);
    m(i, 0) = r.imu[k].t_s;
    for (int j = 0; j < 3; ++j) {
      m(i, 1 + j) = r.imu[k].gyro_radps[j];
      m(i, 4 + j) = r.imu[k].accel_mps2[j];
    }
  }
  d["imu"] = imu;
  py::list stereo;
  for (const runner::StereoImages& s : r.stereo) {
    stereo.append(py::make_tuple(s.t_s, ToArray(s.left), ToArray(s.right)));
  }
  d["stereo_pairs"] = stereo;
  py::list scans;
  for (const robot::RangeScanSample& s : r.scans) {
    scans.append(py::make_tuple(s.t_s, ToArray(s.ranges_m), ToArray(s.angles_rad)));
  }
  d["range_scans"] = scans;
  d["ground_truth"] = ToArray(Eigen::Matrix4d(r.T_world_body.matrix()));
  return d;
}

// A 4x4 matrix from any array-like; ValueError naming the estimate otherwise.
Eigen::Matrix4d Matrix4(const std::string& name,
                        const py::array_t<double, py::array::forcecast>& a) {
  if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4) {
    std::string shape;
    for (py::ssize_t k = 0; k < a.ndim(); ++k)
      shape += (k ? ", " : "") + std::to_string(a.shape(k));
    throw std::invalid_argument("estimate \"" + name +
                                "\": not a rigid transform: expected a 4x4 matrix, got shape (" +
                                shape + ")");
  }
  Eigen::Matrix4d T;
  auto v = a.unchecked<2>();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) T(r, c) = v(r, c);
  }
  return T;
}

// A grayscale image file (the KITTI export's PNGs) as a uint8 array, H x W.
py::array_t<std::uint8_t> ReadImage(const std::string& path) {
  const cv::Mat m = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (m.empty()) throw std::invalid_argument(path + ": cannot read the image");
  if (m.type() != CV_8UC1) throw std::invalid_argument(path + ": not an 8-bit grayscale image");
  py::array_t<std::uint8_t> a({m.rows, m.cols});
  for (int r = 0; r < m.rows; ++r) {
    std::memcpy(a.mutable_data(r, 0), m.ptr(r), static_cast<std::size_t>(m.cols));
  }
  return a;
}

void BindSimulation(py::module_& m) {
  py::class_<Simulation>(m, "_Simulation")
      .def(py::init([](const std::string& path, std::optional<std::uint64_t> seed,
                       const std::vector<std::string>& overrides, const std::string& out,
                       bool images) {
             return std::make_unique<Simulation>(path, Overrides(overrides, seed), out, images);
           }),
           py::arg("scenario_path"), py::arg("seed"), py::arg("overrides"), py::arg("out"),
           py::arg("images"))
      .def_property_readonly("done", &Simulation::done)
      .def_property_readonly("finished", &Simulation::finished)
      .def_property_readonly("t", &Simulation::t_s)
      .def_property_readonly("scenario_json", &Simulation::ScenarioJson)
      .def_property_readonly("seed", [](const Simulation& s) { return s.scenario().seed; })
      .def_property_readonly("duration_s",
                             [](const Simulation& s) { return s.scenario().duration_s; })
      .def_property_readonly("control_period_s",
                             [](const Simulation& s) { return 1.0 / s.scenario().drive.rate_hz; })
      .def(
          "step",
          [](Simulation& s, double l, double r) {
            const runner::StepResult* result = nullptr;
            {
              py::gil_scoped_release simulating;  // the commander calls no Python
              result = &s.Step(l, r);
            }
            return StepDict(*result);
          },
          py::arg("left_mps"), py::arg("right_mps"))
      .def("estimate",
           [](Simulation& s, const std::string& name) -> py::object {
             const std::optional<Eigen::Matrix4d> T = s.Estimate(name);
             if (!T) return py::none();
             return ToArray(*T);
           })
      .def("report_estimate",
           [](Simulation& s, const std::string& name,
              const py::array_t<double, py::array::forcecast>& T) {
             s.ReportEstimate(name, Matrix4(name, T));
           })
      .def("finish", &Simulation::Finish, py::arg("out"));
}

}  // namespace
}  // namespace trackbed::python

PYBIND11_MODULE(_trackbed, m) {
  using namespace trackbed::python;
  m.doc() = "trackbed's compiled core; use the package trackbed (docs/python.md)";
  static py::exception<trackbed::scenario::ScenarioError> scenario_error(m, "ScenarioError",
                                                                         PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const trackbed::scenario::ScenarioError& e) {
      scenario_error(e.what());
    } catch (const std::logic_error& e) {
      // std::invalid_argument is a logic_error too: a bad value, not a bad state.
      if (dynamic_cast<const std::invalid_argument*>(&e)) {
        PyErr_SetString(PyExc_ValueError, e.what());
      } else {
        PyErr_SetString(PyExc_RuntimeError, e.what());
      }
    }
  });
  BindSimulation(m);
  m.def(
      "run",
      [](const std::string& path, const std::string& out, std::optional<std::uint64_t> seed,
         const std::vector<std::string>& overrides) {
        return RunToFolder(path, Overrides(overrides, seed), out);
      },
      py::arg("scenario_path"), py::arg("out"), py::arg("seed"), py::arg("overrides"));
  m.def("read_image", &ReadImage, py::arg("path"));
}
