"""AllanTools' ``Noise`` class: Kasdin & Walter's discrete power-law noise, and the Allan and
modified Allan deviations that noise is expected to show.

N. J. Kasdin and T. Walter, "Discrete simulation of power law noise", Proc. 1992 IEEE Frequency
Control Symposium, pp. 274-283: white noise of variance qd filtered by the causal filter
h_0 = 1, h_k = h_{k-1} (k - 1 - b/2) / k, whose transfer function is (1 - z^-1)^(b/2); the
phase then has the one-sided PSD S_x(f) = g_b f^b with g_b = 2 qd (2 pi)^b tau0^(b+1) (their
eq. 39), i.e. S_y(f) = h_a f^a, a = b + 2, h_a = 2 qd (2 pi)^a tau0^(a-1). b = 0 white PM,
-1 flicker PM, -2 white FM (a random walk of phase), -3 flicker FM, -4 random-walk FM.

The predicted deviations are the continuous-time power-law expressions (NIST SP 1065 Table;
IEEE 1139), with the high cut-off f_h = 1/(2 tau0):
  AVAR: WPM 3 f_h h_2 / (4 pi^2 tau^2); FPM (3 gamma - ln 2 + 3 ln(2 pi f_h tau)) h_1 /
        (4 pi^2 tau^2); WFM h_0 / (2 tau); FFM 2 ln 2 h_-1; RWFM (2 pi^2 / 3) h_-2 tau.
  MVAR: WPM 3 h_2 tau0 / (8 pi^2 tau^3); FPM (24 ln 2 - 9 ln 3) h_1 / (8 pi^2 tau^2);
        WFM h_0 / (4 tau); FFM (27/20) ln 2 h_-1; RWFM (11/20) pi^2 h_-2 tau.
For white PM, white FM and random-walk FM these equal the discrete noise's exact values
(RWFM up to a 1/(2 m^2) relative term); for the flicker noises they hold for long records.
"""
import math

import numpy as np

_EULER_GAMMA = 0.5772156649015329


class Noise:
    """Kasdin-Walter generator: ``Noise(nr, qd, b)``, ``generateNoise()`` fills ``time_series``
    (nr points; phase for b = 0..-4) from NumPy's global generator."""

    def __init__(self, nr=2, qd=1, b=0):
        self.nr, self.qd, self.b = nr, qd, b
        self.time_series = np.array([])

    def set_input(self, nr=2, qd=1, b=0):
        self.nr, self.qd, self.b = nr, qd, b

    def generateNoise(self):
        """White noise of variance qd through the Kasdin-Walter filter (linear convolution by
        FFT over 2 nr points, the first nr kept)."""
        n = int(self.nr)
        white = np.zeros(2 * n)
        white[:n] = np.random.normal(0.0, math.sqrt(self.qd), n)
        k = np.arange(1, n, dtype=np.float64)
        taps = np.zeros(2 * n)
        taps[0] = 1.0
        taps[1:n] = np.cumprod((k - 1.0 - self.b / 2.0) / k)
        self.time_series = np.fft.irfft(np.fft.rfft(white) * np.fft.rfft(taps), 2 * n)[:n]
        return self.time_series

    def phase_psd_from_qd(self, tau0=1.0):
        """g_b of S_x(f) = g_b f^b: 2 qd (2 pi)^b tau0^(b+1)."""
        return 2.0 * self.qd * (2.0 * math.pi) ** self.b * tau0 ** (self.b + 1.0)

    def frequency_psd_from_qd(self, tau0=1.0):
        """h_a of S_y(f) = h_a f^a, a = b + 2: 2 qd (2 pi)^a tau0^(a-1)."""
        a = self.b + 2.0
        return 2.0 * self.qd * (2.0 * math.pi) ** a * tau0 ** (a - 1.0)

    def c_avar(self):
        """Exponent c of tau in AVAR = prefactor^2 tau^c."""
        return {-4: 1.0, -3: 0.0, -2: -1.0, -1: -2.0, 0: -2.0}.get(self.b)

    def c_mvar(self):
        """Exponent c of tau in MVAR = prefactor^2 tau^c."""
        return {-4: 1.0, -3: 0.0, -2: -1.0, -1: -2.0, 0: -3.0}.get(self.b)

    def adev_from_qd(self, tau0=1.0, tau=1.0):
        """sqrt(coefficient h_a): ADEV = this * tau^(c/2) (tau enters flicker PM's log)."""
        h = self.frequency_psd_from_qd(tau0)
        f_h = 0.5 / tau0
        coeff = {
            0: 3.0 * f_h / (4.0 * math.pi ** 2),
            -1: (3.0 * _EULER_GAMMA - math.log(2.0) + 3.0 * math.log(2.0 * math.pi * f_h * tau))
            / (4.0 * math.pi ** 2),
            -2: 0.5,
            -3: 2.0 * math.log(2.0),
            -4: 2.0 * math.pi ** 2 / 3.0,
        }[self.b]
        return math.sqrt(coeff * h)

    def mdev_from_qd(self, tau0=1.0, tau=1.0):
        """sqrt(coefficient h_a): MDEV = this * tau^(c/2)."""
        h = self.frequency_psd_from_qd(tau0)
        coeff = {
            0: 3.0 * tau0 / (8.0 * math.pi ** 2),
            -1: (24.0 * math.log(2.0) - 9.0 * math.log(3.0)) / (8.0 * math.pi ** 2),
            -2: 0.25,
            -3: 27.0 / 20.0 * math.log(2.0),
            -4: 11.0 / 20.0 * math.pi ** 2,
        }[self.b]
        return math.sqrt(coeff * h)

    def adev(self, tau0, tau):
        """Expected Allan deviation at tau (s) for samples tau0 (s) apart."""
        return self.adev_from_qd(tau0=tau0, tau=tau) * tau ** (self.c_avar() / 2.0)

    def mdev(self, tau0, tau):
        """Expected modified Allan deviation at tau (s) for samples tau0 (s) apart."""
        return self.mdev_from_qd(tau0=tau0, tau=tau) * tau ** (self.c_mvar() / 2.0)
