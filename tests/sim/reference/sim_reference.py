#!/usr/bin/env python3
"""Independent re-implementation of the simulator's random streams, for golden test values.

Python floats are IEEE-754 doubles with no fused multiply-add, so re-doing the C++ operations
in the same order must reproduce the C++ results bit for bit; tests/sim/rng_test.cpp checks
the values printed here. The xoshiro256** jump is checked by a GF(2) matrix power instead of
the published jump polynomials, so that those constants are verified, not copied.
Run: python3 sim_reference.py
"""
import math
import re
import struct
from pathlib import Path

M64 = (1 << 64) - 1


def splitmix64(seed):
    state = seed
    while True:
        state = (state + 0x9E3779B97F4A7C15) & M64
        z = state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & M64
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & M64
        yield z ^ (z >> 31)


def rotl(x, k):
    return ((x << k) | (x >> (64 - k))) & M64


class Xoshiro:
    def __init__(self, state):
        self.s = list(state)

    def __call__(self):
        s = self.s
        result = (rotl((s[1] * 5) & M64, 7) * 9) & M64
        t = (s[1] << 17) & M64
        s[2] ^= s[0]
        s[3] ^= s[1]
        s[1] ^= s[2]
        s[0] ^= s[3]
        s[2] ^= t
        s[3] = rotl(s[3], 45)
        return result

    def uniform(self):
        return float(self() >> 11) * 2.0 ** -53


# ---- the jump as a matrix power over GF(2) -------------------------------------------------
def state_to_int(s):
    return s[0] | (s[1] << 64) | (s[2] << 128) | (s[3] << 192)


def int_to_state(v):
    return [(v >> (64 * i)) & M64 for i in range(4)]


def transition_columns():
    """Column j = image of unit vector e_j under one step of the linear engine."""
    cols = []
    for j in range(256):
        x = Xoshiro(int_to_state(1 << j))
        x()
        cols.append(state_to_int(x.s))
    return cols


def apply(cols, v):
    out = 0
    j = 0
    while v:
        if v & 1:
            out ^= cols[j]
        v >>= 1
        j += 1
    return out


def square(cols):
    return [apply(cols, c) for c in cols]


def power_of_two_steps(k):
    cols = transition_columns()
    for _ in range(k):
        cols = square(cols)
    return cols


# ---- portable math, same operation order as src/sim/portable_math.cpp ----------------------
LN2_HI = float.fromhex("0x1.62e42fee00000p-1")
LN2_LO = float.fromhex("0x1.a39ef35793c76p-33")
INV_LN2 = float.fromhex("0x1.71547652b82fep0")
FACT = [math.factorial(i) for i in range(23)]


def expm1_series(r):
    p = 1.0 / float(FACT[22])
    for n in range(21, 2, -1):
        p = 1.0 / float(FACT[n]) + r * p
    p = 0.5 + r * p
    return r + (r * r) * p


def p_exp(x):
    k = float(round(x * INV_LN2))
    r = (x - k * LN2_HI) - k * LN2_LO
    e = 1.0 + expm1_series(r)
    ki = int(k)
    half = int(ki / 2)  # C++ integer division truncates toward zero
    return math.ldexp(math.ldexp(e, half), ki - half)


def p_log(x):
    m, e = math.frexp(x)
    if m < float.fromhex("0x1.6a09e667f3bcdp-1"):
        m *= 2.0
        e -= 1
    f = m - 1.0
    s = f / (2.0 + f)
    s2 = s * s
    p = 1.0 / 25.0
    for d in range(23, 2, -2):
        p = 1.0 / d + s2 * p
    log_m = 2.0 * s + 2.0 * s * (s2 * p)
    de = float(e)
    return de * LN2_HI + (de * LN2_LO + log_m)


# ---- ziggurat --------------------------------------------------------------------------------
def load_tables():
    text = (Path(__file__).resolve().parents[3] / "src/sim/ziggurat_tables.inc").read_text()

    def arr(name):
        body = re.search(name + r"\[257\] = \{(.*?)\};", text, re.S).group(1)
        return [float.fromhex(t) for t in re.findall(r"-?0x[0-9a-f.p+-]+", body)]

    def scalar(name):
        return float.fromhex(re.search(name + r" = (-?0x[0-9a-f.p+-]+);", text).group(1))

    return scalar("kZigguratR"), scalar("kZigguratInvR"), arr("kZigguratX"), arr("kZigguratF")


R, INV_R, ZX, ZF = load_tables()


def normal(eng):
    bits = eng()
    while True:
        layer = bits & 0xFF
        neg = bool(bits & 0x100)
        u = float(bits >> 11) * 2.0 ** -53
        a = u * ZX[layer]
        if a < ZX[layer + 1]:
            return -a if neg else a
        if layer == 0:
            while True:
                ta = -p_log(1.0 - eng.uniform()) * INV_R
                tb = -p_log(1.0 - eng.uniform())
                if tb + tb > ta * ta:
                    x = R + ta
                    return -x if neg else x
        y = ZF[layer] + eng.uniform() * (ZF[layer + 1] - ZF[layer])
        if y < p_exp(-0.5 * a * a):
            return -a if neg else a
        bits = eng()


def seeded(seed):
    g = splitmix64(seed)
    return [next(g) for _ in range(4)]



# ---- the generator (src/sim/generator.cpp, flicker.cpp, gauss_markov.cpp) -----------------
def p_expm1(x):
    if abs(x) < 1.0:
        return expm1_series(x)
    if x < -40.0:
        return -1.0
    return p_exp(x) - 1.0


TWO_PI = float.fromhex("0x1.921fb54442d18p2")


def sincos_cycles(c):
    t = c - float(round(c))
    q = float(round(4.0 * t))
    u = t - 0.25 * q
    a = TWO_PI * u
    a2 = a * a
    ps = -1.0 / float(FACT[19])
    for n, sign in ((17, 1), (15, -1), (13, 1), (11, -1), (9, 1), (7, -1), (5, 1), (3, -1)):
        ps = sign / float(FACT[n]) + a2 * ps
    s = a + a * (a2 * ps)
    pc = 1.0 / float(FACT[18])
    for n, sign in ((16, -1), (14, 1), (12, -1), (10, 1), (8, -1), (6, 1), (4, -1)):
        pc = sign / float(FACT[n]) + a2 * pc
    pc = 0.5 + a2 * pc
    co = 1.0 - a2 * pc
    return {0: (s, co), 1: (co, -s), -1: (-co, s)}.get(int(q), (-s, -co))


def gm_g(x):
    if x < 1.0:
        term = x * x * x / 6.0
        total = 0.0
        sign = -1.0
        pow2 = 4.0
        for n in range(3, 31):
            total += sign * (2.0 - pow2) * term
            term = term * x / float(n + 1)
            sign = -sign
            pow2 *= 2.0
        return total
    e1 = p_exp(-x)
    return (x - 1.5) + (2.0 * e1 - 0.5 * (e1 * e1))


def gm_step(sigma, time_s, h):
    x = h / time_s
    e1 = -p_expm1(-x)
    one_minus_phi2 = e1 * (2.0 - e1)
    phi = 1.0 - e1
    state_noise = sigma * math.sqrt(one_minus_phi2)
    mean_of_state = e1 / x
    mean_of_z1 = sigma * (e1 * e1) / (x * math.sqrt(one_minus_phi2))
    residual = 2.0 * gm_g(x) - (e1 * e1 * e1) / (2.0 - e1)
    mean_of_z2 = (sigma / x) * math.sqrt(residual) if residual > 0.0 else 0.0
    return phi, state_noise, mean_of_state, mean_of_z1, mean_of_z2


def flicker_bank(b, tau_min, tau_max):
    ln_r = p_log(10.0) / 1.5
    r = p_exp(ln_r)
    t_lo = tau_min / 16.0
    span = p_log(tau_max * 8.0 / t_lo) / ln_r
    count = math.ceil(span - 1e-9) + 1
    variance = b * b * ln_r / math.pi
    poles = []
    for i in range(count):
        t = t_lo * p_exp(ln_r * float(i))
        v = variance * r / (r - 1.0) if i == count - 1 else variance
        poles.append((math.sqrt(v), t))
    white = math.sqrt(2.0 * variance * t_lo / (r - 1.0))
    return poles, white


def make_stream(seed, channel, term):
    state = state_to_int(seeded(seed))
    global _J128, _J192
    if channel:
        state = apply(_J192, state) if channel == 1 else None
    for _ in range(term):
        state = apply(_J128, state)
    return Xoshiro(int_to_state(state))


def simulate(model, rate, n, seed, channel):
    """model: dict with q, n, b, k, r, gm_sigma, gm_time, sine_amp, sine_freq, sine_phase, bias."""
    h = 1.0 / rate
    duration = float(n) / rate
    streams = [make_stream(seed, channel, t) for t in range(5)]
    normal_of = lambda t: normal(streams[t])
    y = [0.0] * n
    if model.get("q", 0.0) > 0.0:
        q = model["q"]
        prev = q * normal_of(0)
        inv_h = 1.0 / h
        for k in range(n):
            e = q * normal_of(0)
            y[k] += (e - prev) * inv_h
            prev = e
    if model.get("n", 0.0) > 0.0:
        s = model["n"] / math.sqrt(h)
        for k in range(n):
            y[k] += s * normal_of(1)
    if model.get("b", 0.0) > 0.0:
        poles, white = flicker_bank(model["b"], 1.0 / rate, max(duration, 10.0 * (1.0 / rate)))
        steps = [gm_step(sg, t, h) for sg, t in poles]
        res_var = white * white / h
        for st in steps:
            res_var += st[4] * st[4]
        residual = math.sqrt(res_var)
        states = [sg * normal_of(2) for sg, _ in poles]
        for k in range(n):
            z = [normal_of(2) for _ in range(len(poles) + 1)]
            even = residual * z[len(poles)]
            odd = 0.0
            for i, st in enumerate(steps):
                w = states[i]
                contribution = st[2] * w + st[3] * z[i]
                if i & 1:
                    odd += contribution
                else:
                    even += contribution
                states[i] = st[0] * w + st[1] * z[i]
            y[k] += even + odd
    if model.get("k", 0.0) > 0.0:
        half = model["k"] * math.sqrt(h) * 0.5
        bridge = model["k"] * math.sqrt(h) / math.sqrt(12.0)
        step = 2.0 * half
        rate_rw = 0.0
        for k in range(n):
            z1 = normal_of(3)
            z2 = normal_of(3)
            y[k] += rate_rw + (half * z1 + bridge * z2)
            rate_rw += step * z1
    if model.get("r", 0.0) != 0.0:
        rr = model["r"] * h
        for k in range(n):
            y[k] += rr * (float(k) + 0.5)
    if model.get("gm_sigma", 0.0) > 0.0:
        st = gm_step(model["gm_sigma"], model["gm_time"], h)
        w = model["gm_sigma"] * normal_of(4)
        for k in range(n):
            z1 = normal_of(4)
            z2 = normal_of(4)
            y[k] += st[2] * w + (st[3] * z1 + st[4] * z2)
            w = st[0] * w + st[1] * z1
    if model.get("sine_amp", 0.0) > 0.0:
        fh = model["sine_freq"] * h
        x = math.pi * fh
        sinc = 1.0 if x == 0.0 else sincos_cycles(0.5 * fh)[0] / x
        gain = model["sine_amp"] * sinc
        c0 = model["sine_phase"] / (2.0 * math.pi)
        for k in range(n):
            y[k] += gain * sincos_cycles(fh * (float(k) + 0.5) + c0)[0]
    if model.get("bias", 0.0) != 0.0:
        for k in range(n):
            y[k] += model["bias"]
    return y


def fingerprint(values):
    h = 0xCBF29CE484222325
    for v in values:
        u = int.from_bytes(struct.pack("<d", v), "little")
        for _ in range(8):
            h ^= u & 0xFF
            h = (h * 0x100000001B3) & M64
            u >>= 8
    return h


_J128 = None
_J192 = None

if __name__ == "__main__":
    g = splitmix64(1234567)
    print("splitmix64(1234567):", [next(g) for _ in range(5)])
    x = Xoshiro([1, 2, 3, 4])
    print("xoshiro256** from {1,2,3,4}:", [x() for _ in range(10)])
    base = seeded(42)
    print("seed 42 state:", [hex(w) for w in base])
    j128 = power_of_two_steps(128)
    after = int_to_state(apply(j128, state_to_int(base)))
    print("seed 42 after 2^128 steps:", [hex(w) for w in after])
    j192 = j128
    for _ in range(64):
        j192 = square(j192)
    _J128, _J192 = j128, j192
    after = int_to_state(apply(j192, state_to_int(base)))
    print("seed 42 after 2^192 steps:", [hex(w) for w in after])
    eng = Xoshiro(seeded(7))
    vals = [normal(eng) for _ in range(200000)]
    print("seed 7 normals 0..7:", [v.hex() for v in vals[:8]])
    print("seed 7 normal 199999:", vals[-1].hex())
    print("seed 7 sum of 200000 normals:", math.fsum(vals).hex(), math.fsum(vals))
    print("engine state after:", [hex(w) for w in eng.s])
    gyro3 = dict(q=0.001e-4, n=8.8e-4, b=5.8e-4, k=0.09e-4)
    print("fingerprint tg100 gyro3, seed 1, channel 1, 4096 samples: 0x%x"
          % fingerprint(simulate(gyro3, 200.0, 4096, 1, 1)))
    full = dict(q=1e-5, n=8.9e-4, b=5.9e-4, k=1.5e-5, r=1e-6, gm_sigma=2e-3, gm_time=0.7,
                sine_amp=3e-3, sine_freq=1.7, sine_phase=0.4, bias=-0.25)
    print("fingerprint full model, seed 42, channel 0, 4096 samples: 0x%x"
          % fingerprint(simulate(full, 200.0, 4096, 42, 0)))
