"""Wave speeds of the classical (long-wave) elastic solid of a resolved material (the
`material` block of summary.json), shared by the case folders' checks and reports."""
import math


def rayleigh_speed(material):
    """Rayleigh wave speed: the root xi = c_R / c_s in (0, 1) of
    (2 - xi^2)^2 = 4 sqrt(1 - xi^2) sqrt(1 - xi^2 c_s^2 / c_p^2)."""
    rho = material["density"] * material["solid_fraction"]
    lam, mu = material["lambda"], material["mu"]
    cs, cp = math.sqrt(mu / rho), math.sqrt((lam + 2 * mu) / rho)
    k = (cs / cp) ** 2
    f = lambda x: (2 - x * x) ** 2 - 4 * math.sqrt(1 - x * x) * math.sqrt(1 - k * x * x)  # noqa: E731
    # f < 0 just above the trivial root 0 and up to c_R, f > 0 from there to c_s (f(1) = 1): for
    # Poisson ratios in [0, 0.5) the root lies in [0.87, 0.96] c_s, which [0.5, 1) brackets.
    lo, hi = 0.5, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(mid) < 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi) * cs
