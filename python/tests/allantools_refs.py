"""Reference data for the AllanTools-layer tests, generated from their published definitions
(/work/shared/references.md): the NBS14 sets (NIST SP 1065) and Stable32's PHASE.DAT."""
import numpy as np

# NBS14 10-point set: fractional frequency and its published phase (tau0 = 1 s).
NBS10_FREQ = np.array([892, 809, 823, 798, 671, 644, 883, 903, 677], dtype=float)
NBS10_PHASE = np.array([0, 103.11111, 123.22222, 157.33333, 166.44444, 48.55555, -96.33333,
                        -2.22222, 111.88889, 0])


def nbs14_1000():
    """Lehmer generator n0 = 1234567890, n_{i+1} = 16807 n_i mod (2^31 - 1), y_i = n_i / (2^31 - 1)."""
    n, out = 1234567890, []
    for _ in range(1000):
        out.append(n / 2147483647.0)
        n = (16807 * n) % 2147483647
    return np.array(out)


def phase_dat():
    """PHASE.DAT: the 1000-point set, mean removed, integrated from x0 = 0 (1001 points)."""
    y = nbs14_1000()
    return np.concatenate(([0.0], np.cumsum(y - y.mean())))
