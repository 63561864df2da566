"""AllanTools' real-time statistics (``oadev_realtime``, ``ohdev_realtime``, ``tdev_realtime``):
deviations updated sample by sample from a stream of phase, at fixed averaging factors or at
factors added automatically (about ``pts_per_decade`` per decade) as the record grows.

Each new phase sample x_i adds one term per averaging factor m (Dobrogowski & Kasznia, "Real-time
assessment of Allan deviation and time deviation", 2007): the second difference
x_i - 2 x_{i-m} + x_{i-2m} squared (oadev, n = N - 2m), the third difference squared (ohdev,
n = N - 3m), or, for tdev, the running m-sum of second differences, advanced by the third
difference x_i - 3 x_{i-m} + 3 x_{i-2m} - x_{i-3m}, squared (n = N - 3m + 1). After N samples
``devs()`` equals the batch oadev / ohdev / tdev of the same samples.
"""
import numpy as np


class dev_realtime:
    """Common part: the phase record ``x``, the factors ``afs``, the deviations ``dev``."""

    def __init__(self, afs=[1], tau0=1.0, auto_afs=False, pts_per_decade=4):
        self.x = []
        self.tau0 = tau0
        self.auto_afs = auto_afs
        # candidate factors of one decade: round(10^d * 10^(k / pts_per_decade))
        self.af_taus = np.logspace(0, 1, pts_per_decade + 1)[:-1]
        self.af_idx = 0
        self.af_decade = 0
        self.afs = np.array([1]) if auto_afs else np.array(afs)
        self.dev = np.zeros(len(self.afs))
        self._reset_state(len(self.afs))

    # subclasses: _reset_state(k), _append_state(), _update(idx, af, i) adds the term that ends
    # at sample i

    def add_phase(self, xnew):
        """Adds one phase sample (s) and updates every factor that has a new term."""
        self.x.append(xnew)
        i = len(self.x) - 1
        for idx, af in enumerate(self.afs):
            self._update(idx, int(af), i)
        if self.auto_afs:
            self.update_af()

    def add_frequency(self, f):
        """Adds a frequency sample as the next phase x[-1] + f (AllanTools' convention: the
        first call starts the phase at 0; no tau0 factor)."""
        if not self.x:
            self.add_phase(0)
        self.add_phase(self.x[-1] + f)

    def update_af(self):
        """Auto-AF mode: adds the next candidate factor once 2 af + 1 samples exist."""
        idx, decade = self.af_idx + 1, self.af_decade
        if idx == len(self.af_taus):
            idx, decade = 0, decade + 1
        next_af = int(np.round(10.0 ** decade * self.af_taus[idx]))
        if len(self.x) >= 2 * next_af + 1:
            self.afs = np.append(self.afs, next_af)
            self.dev = np.append(self.dev, 0.0)
            self._append_state()
            # the terms that end at samples already recorded (AllanTools misses the first)
            for i in range(len(self.x)):
                self._update(len(self.afs) - 1, next_af, i)
            self.af_idx, self.af_decade = idx, decade

    def taus(self):
        """Averaging times (s): tau0 * afs."""
        return self.tau0 * np.array(self.afs)

    def devs(self):
        return self.dev


class _difference_realtime(dev_realtime):
    """A deviation from the running sum S of squared differences of the phase, updated per
    sample; subclasses give the difference's weights (newest sample first) and its norm."""

    _weights = ()
    _norm = 1.0

    def _reset_state(self, k):
        self.S = np.zeros(k)

    def _append_state(self):
        self.S = np.append(self.S, 0.0)

    def _update(self, idx, af, i):
        x = self.x
        order = len(self._weights) - 1
        if i < order * af:
            return
        d = sum(w * x[i - j * af] for j, w in enumerate(self._weights))
        self.S[idx] += d ** 2
        self.dev[idx] = np.sqrt(
            self.S[idx] / (self._norm * (af * self.tau0) ** 2 * (i + 1 - order * af)))


class oadev_realtime(_difference_realtime):
    """Overlapping Allan deviation, updated per sample (squared second differences)."""

    _weights = (1, -2, 1)
    _norm = 2.0


class ohdev_realtime(_difference_realtime):
    """Overlapping Hadamard deviation, updated per sample (squared third differences)."""

    _weights = (1, -3, 3, -1)
    _norm = 6.0


class tdev_realtime(dev_realtime):
    """Time deviation (and, through mdev(), the modified Allan deviation), updated per sample.

    S is the current m-sum of second differences, So the sum of its squares."""

    def _reset_state(self, k):
        self.S = np.zeros(k)
        self.So = np.zeros(k)

    def _append_state(self):
        self.S = np.append(self.S, 0.0)
        self.So = np.append(self.So, 0.0)

    def _update(self, idx, af, i):
        x = self.x
        if i < 2 * af:
            return
        if i < 3 * af:  # building the first m-sum, x[2m..3m-1]
            self.S[idx] += x[i] - 2 * x[i - af] + x[i - 2 * af]
            if i == 3 * af - 1:
                self.So[idx] = self.S[idx] ** 2
                self._set_dev(idx, af, i)
            return
        self.S[idx] += x[i] - 3 * x[i - af] + 3 * x[i - 2 * af] - x[i - 3 * af]
        self.So[idx] += self.S[idx] ** 2
        self._set_dev(idx, af, i)

    def _set_dev(self, idx, af, i):
        n = i + 1 - 3 * af + 1
        self.dev[idx] = np.sqrt(self.So[idx] / (6.0 * n * af * af))

    def mdev(self):
        """Modified Allan deviation: tdev sqrt(3) / tau."""
        return self.dev * np.sqrt(3) / (np.array(self.afs) * self.tau0)
