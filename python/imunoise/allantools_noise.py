"""Power-law noise generators of the AllanTools interface (``imunoise.allantools.noise``).

Same names, parameters and scaling as AllanTools' ``noise`` module, drawing from NumPy's global
generator (``np.random.seed`` makes a run repeatable, as with AllanTools; the draws themselves
are not AllanTools' sample for sample). PSDs are one-sided, in X^2/Hz for samples in X.
For imunoise's own simulator (every inertial-sensor noise term, bit-reproducible from a seed)
use ``imunoise.simulate``.
"""
import math

import numpy as np


def white(num_points=1024, b0=1.0, fs=1.0):
    """White noise with one-sided PSD b0 from 0 to fs/2: variance b0 fs / 2."""
    return math.sqrt(b0 * fs / 2.0) * np.random.randn(num_points)


def brown(num_points=1024, b_minus2=1.0, fs=1.0):
    """Random walk with PSD b_minus2 / f^2: the integral (cumulative sum / fs) of white noise of
    PSD b_minus2 (2 pi)^2, since integration divides a PSD by (2 pi f)^2."""
    return np.cumsum(white(num_points, b0=b_minus2 * (2.0 * math.pi) ** 2, fs=fs)) / float(fs)


def violet(num_points=1024, b2=1.0, fs=1.0):
    """Violet noise with PSD b2 f^2: the derivative (first difference times fs) of white noise
    of PSD b2 / (2 pi)^2, num_points + 1 white samples differenced to num_points."""
    return float(fs) * np.diff(white(num_points + 1, b0=b2 / (2.0 * math.pi) ** 2, fs=fs))


def pink(num_points=1024, depth=80):
    """Flicker (1/f) noise, Voss-McCartney: the sum of ``depth`` rows of unit normal values,
    row k redrawn every 2^k samples (at a random phase), plus a white unit normal per sample.

    The PSD falls as 1/f over the octaves the rows span (log2(num_points) of them); rows slower
    than the record are constant, an offset. Not normalised (AllanTools' convention).
    """
    n = int(num_points)
    out = np.random.randn(n)
    index = np.arange(n)
    rows = min(int(depth), max(1, int(math.ceil(math.log2(max(n, 2)))) + 1))
    for k in range(rows):
        period = 1 << k
        start = np.random.randint(period)
        values = np.random.randn((n + start) // period + 1)
        out += values[(index + start) >> k]
    if depth > rows:
        out += np.random.randn(int(depth) - rows).sum()
    return out


def numpy_psd(x, f_sample=1.0):
    """One-sided periodogram of x: (f, psd), psd = 2 |rfft(x)|^2 / (N f_sample) in X^2/Hz,
    f from 0 to f_sample/2."""
    x = np.asarray(x, dtype=np.float64)
    psd = 2.0 / (len(x) * f_sample) * np.abs(np.fft.rfft(x)) ** 2
    return np.linspace(0.0, f_sample / 2.0, len(psd)), psd


def scipy_psd(x, f_sample=1.0, nr_segments=4):
    """Welch PSD from SciPy (needs SciPy, which imunoise itself does not)."""
    try:
        import scipy.signal
    except ImportError as e:  # pragma: no cover - depends on the machine
        raise ImportError("noise.scipy_psd needs SciPy; use noise.numpy_psd instead") from e
    return scipy.signal.welch(x, f_sample, nperseg=int(len(x) / nr_segments))


def timmer_koenig_from_psd(f_nodes, h, alpha, duration, timestep, output="phase", seed=None):
    """Noise with the piecewise power-law one-sided PSD S_y(f) = h[k] f^alpha[k] (fractional
    frequency; segments and f_nodes as in ``adev2psd_piecewise_approx``), by Fourier synthesis
    (Timmer & Koenig 1995): n = round(duration / timestep) samples; at each DFT frequency
    f_j = j / (n timestep), 0 < j <= n/2, a complex normal coefficient with E|X_j|^2 =
    S(f_j) n / (2 timestep) (real at the Nyquist bin), the DC bin 0, then the inverse real FFT.

    output "phase": time x in s, S_x = S_y / (2 pi f)^2; "frequency": y. ``seed`` seeds a
    NumPy Generator (None: a fresh one). The record holds no power below 1 / duration, so
    deviations at tau above about duration / 10 come out low.
    """
    from .allantools_psd import piecewise_psd
    if output not in ("phase", "frequency"):
        raise ValueError(f"output must be 'phase' or 'frequency', got {output!r}")
    if not (timestep > 0 and math.isfinite(timestep) and duration > 0 and math.isfinite(duration)):
        raise ValueError("duration and timestep must be positive and finite (s)")
    n = int(round(duration / timestep))
    if n < 2:
        raise ValueError(f"duration / timestep = {duration / timestep:g}: need at least 2 samples")
    rng = np.random.default_rng(seed)
    f = np.fft.rfftfreq(n, timestep)[1:]
    psd = piecewise_psd(f, h, alpha, f_nodes)
    if output == "phase":
        psd = psd / (2.0 * math.pi * f) ** 2
    sigma = np.sqrt(psd * n / (4.0 * timestep))  # per real and imaginary part
    coeff = np.zeros(len(f) + 1, dtype=complex)
    coeff[1:] = sigma * (rng.standard_normal(len(f)) + 1j * rng.standard_normal(len(f)))
    if n % 2 == 0:  # the Nyquist coefficient is real: all of E|X|^2 in one part
        coeff[-1] = math.sqrt(2.0) * sigma[-1] * rng.standard_normal()
    return np.fft.irfft(coeff, n)
