#!/usr/bin/env python3
"""Prints the polynomial coefficients of the division-free log and cos used by the Gaussian noise, and
of the arctangent the render pass projects directions with (compute_shaders/include/carbtf_gpu_shared.h).
Rerun to reproduce them; nothing reads this at build time.

Why polynomials: docs/design.md 4.4 asks for CPU float32 and GPU noise that agree bit for bit. Vulkan only
guarantees correctly rounded +, - and *, so log and cos are built from those alone.

  ln(1+x), x in [sqrt(1/2)-1, sqrt(2)-1]: Chebyshev interpolant, degree LOG_DEGREE, as monomials in x.
  cos(2*pi*r), r in [0, 1/4]: Chebyshev interpolant in z = r*r, degree COS_DEGREE, as monomials in z.
  atan(t) = t * P(t*t), t in [0, 1]: Chebyshev interpolant of atan(sqrt z)/sqrt z, degree ATAN_DEGREE.
  Vulkan allows atan 4096 ULP of error, enough to move a direction's interpolation weights by 1e-3;
  the polynomial keeps the GPU within 1e-7 of the CPU, which scene pruning relies on.
"""
import math
from fractions import Fraction

LOG_DEGREE = 13
COS_DEGREE = 7
ATAN_DEGREE = 10


def chebyshev_monomials(f, a, b, degree):
    n = degree + 1
    nodes = [math.cos(math.pi * (k + 0.5) / n) for k in range(n)]
    values = [f(0.5 * (b - a) * t + 0.5 * (b + a)) for t in nodes]
    cheb = [2.0 / n * sum(values[k] * math.cos(j * math.pi * (k + 0.5) / n) for k in range(n))
            for j in range(n)]
    cheb[0] *= 0.5
    t_polys = [[Fraction(1)], [Fraction(0), Fraction(1)]]
    for j in range(2, n):
        prev, prev2 = t_polys[j - 1], t_polys[j - 2]
        nxt = [Fraction(0)] + [2 * c for c in prev]
        for i, c in enumerate(prev2):
            nxt[i] -= c
        t_polys.append(nxt)
    in_t = [Fraction(0)] * n
    for j in range(n):
        for i, c in enumerate(t_polys[j]):
            in_t[i] += Fraction(cheb[j]) * c
    fa, fb = Fraction(a), Fraction(b)
    scale, shift = 2 / (fb - fa), -(fa + fb) / (fb - fa)
    in_x = [Fraction(0)] * n
    power = [Fraction(1)]
    for i in range(n):
        for k, c in enumerate(power):
            in_x[k] += in_t[i] * c
        nxt = [Fraction(0)] * (len(power) + 1)
        for k, c in enumerate(power):
            nxt[k] += shift * c
            nxt[k + 1] += scale * c
        power = nxt
    return in_x


def as_float32(value):
    import struct
    return struct.unpack('<f', struct.pack('<f', float(value)))[0]


def max_error(f, coefficients, a, b, samples=20001):
    worst = 0.0
    for s in range(samples):
        x = a + (b - a) * s / (samples - 1)
        p = 0.0
        for c in reversed(coefficients):
            p = p * x + as_float32(c)
        worst = max(worst, abs(p - f(x)))
    return worst


if __name__ == "__main__":
    lo, hi = math.sqrt(0.5) - 1.0, math.sqrt(2.0) - 1.0
    cos_f = lambda z: math.cos(2 * math.pi * math.sqrt(z))  # noqa: E731
    log_c = chebyshev_monomials(math.log1p, lo, hi, LOG_DEGREE)
    log_c[0] = Fraction(0)  # through the origin, so ln(1) is exactly 0
    cos_c = chebyshev_monomials(cos_f, 0.0, 1.0 / 16.0, COS_DEGREE)
    for name, coeffs, f, a, b in (("LOG1P", log_c, math.log1p, lo, hi),
                                  ("COS2PI", cos_c, cos_f, 0.0, 1.0 / 16.0)):
        print(f"// {name}: max abs error {max_error(f, coeffs, a, b):.1e} (float32 coefficients, "
              f"double evaluation)")
        for i, c in enumerate(coeffs):
            if name == "LOG1P" and i == 0:
                continue
            print(f"CARBTF_CONST_FLOAT(CARBTF_{name}_C{i}, {as_float32(c):.9e}f)")
    atan_f = lambda z: math.atan(math.sqrt(z)) / math.sqrt(z) if z > 0 else 1.0  # noqa: E731
    atan_c = chebyshev_monomials(atan_f, 0.0, 1.0, ATAN_DEGREE)
    print(f"// ATAN: max abs error of atan(t)/t {max_error(atan_f, atan_c, 0.0, 1.0):.1e} (float32 coefficients, "
          f"double evaluation)")
    for i, c in enumerate(atan_c):
        print(f"CARBTF_CONST_FLOAT(CARBTF_ATAN_C{i}, {as_float32(c):.9e}f)")
