// The noise simulator from Python: a model's samples as a NumPy array.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <string>

#include "imunoise/error.hpp"
#include "imunoise/sim/generator.hpp"
#include "imunoise/sim/presets.hpp"

namespace py = pybind11;

namespace imunoise::python {
namespace {

std::size_t sample_count(double rate_hz, double duration_s) {
  if (!(rate_hz > 0) || !std::isfinite(rate_hz)) throw InputError("rate must be positive (Hz)");
  if (!(duration_s > 0) || !std::isfinite(duration_s)) throw InputError("duration must be positive (s)");
  return static_cast<std::size_t>(std::llround(duration_s * rate_hz));
}

py::array_t<double> to_array(std::vector<double>&& samples) {
  auto* owned = new std::vector<double>(std::move(samples));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>(static_cast<py::ssize_t>(owned->size()), owned->data(), free_when_done);
}

// Parameters in the rate unit the caller works in (deg/s for a gyro in deg/s).
py::array_t<double> simulate(double rate, double duration, double Q, double N, double B, double K,
                             double R, double bias, double gm_sigma, double gm_tau, double sine_amp,
                             double sine_freq, std::uint64_t seed, std::uint64_t channel) {
  sim::NoiseModel model;
  model.q_unit_s = Q;
  model.n_unit_sqrt_s = N;
  model.b_unit = B;
  model.k_unit_per_sqrt_s = K;
  model.r_unit_per_s = R;
  model.bias_unit = bias;
  model.gm_sigma_unit = gm_sigma;
  model.gm_time_s = gm_tau;
  model.sine_amplitude_unit = sine_amp;
  model.sine_frequency_hz = sine_freq;
  const std::size_t n = sample_count(rate, duration);
  std::vector<double> samples;
  {
    py::gil_scoped_release release;
    samples = sim::simulate(model, rate, n, seed, channel);
  }
  return to_array(std::move(samples));
}

// A preset's channels as a 2-D array (samples x channels) and the rate.
py::tuple simulate_preset(const std::string& name, double duration, std::uint64_t seed) {
  const sim::Preset preset = sim::find_preset(name);
  const std::size_t n = sample_count(preset.rate_hz, duration);
  py::array_t<double> out({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(preset.channels.size())});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t c = 0; c < preset.channels.size(); ++c) {
    std::vector<double> samples;
    {
      py::gil_scoped_release release;
      samples = sim::simulate(preset.channels[c], preset.rate_hz, n, seed, c);
    }
    for (std::size_t i = 0; i < n; ++i) view(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(c)) = samples[i];
  }
  return py::make_tuple(out, preset.rate_hz, preset.unit);
}

}  // namespace

void register_simulate(py::module_& m) {
  m.def("simulate", &simulate, py::arg("rate"), py::arg("duration"), py::arg("Q") = 0.0,
        py::arg("N") = 0.0, py::arg("B") = 0.0, py::arg("K") = 0.0, py::arg("R") = 0.0,
        py::arg("bias") = 0.0, py::arg("gm_sigma") = 0.0, py::arg("gm_tau") = 0.0,
        py::arg("sine_amp") = 0.0, py::arg("sine_freq") = 0.0, py::arg("seed") = 1,
        py::arg("channel") = 0,
        "Simulated rate samples (same unit as the parameters: Q unit*s, N unit*sqrt(s), B unit, "
        "K unit/sqrt(s), R unit/s) at `rate` Hz for `duration` s; reproducible from `seed`.");
  m.def("simulate_preset", &simulate_preset, py::arg("name"), py::arg("duration") = 21600.0,
        py::arg("seed") = 1,
        "A preset's channels (e.g. 'tg100': the paper's four gyros) -> (samples[n, channels], rate_hz, unit)");
}

}  // namespace imunoise::python
