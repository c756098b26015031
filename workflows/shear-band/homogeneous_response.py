"""Homogeneous plane-strain biaxial response of the case material, for the report.

Why: the specimen can only form shear bands once its material softens, and with a
Drucker-Prager cone in plane strain the material keeps hardening long after first yield,
because sigma_zz has to build up to the plane-strain limit state (solver/plasticity/README.md,
"Cone matches"). This module integrates the homogeneous state of the case's loading
(sigma_xx = -confinement held, eps_yy driven, eps_zz = 0) so the report can say where the
homogeneous peak lies against the case's platen travel.

The homogeneous state has no curvature and a symmetric stress, so the micro-polar
Drucker-Prager model of docs/theory.md section 6 reduces to the classical one: f = q + M_phi p - k c,
g = q + M_psi p, c = max(c0 + h ebar, c_res), d ebar = d gamma on the cone. The update is the
rate-independent backward-Euler return (the viscous overstress eta ebar' is ~1e4 Pa s x 0.5/s
= 5 kPa here, 0.3 % of the strength, and is left out). Cone coefficients: the formulas of
solver/plasticity/README.md for both matches. Independent of the solver (pure Python), so it
is also a cross-check of the runs' pre-peak load.
"""
import math

import numpy as np


def cone_coefficients(friction_deg, dilatancy_deg, match):
    """(M_phi, M_psi, k/c) of solver/plasticity/README.md."""
    sp, ss = math.sin(math.radians(friction_deg)), math.sin(math.radians(dilatancy_deg))
    cp = math.cos(math.radians(friction_deg))
    if match == "triaxial-compression":
        return 6 * sp / (3 - sp), 6 * ss / (3 - ss), 6 * cp / (3 - sp)
    if match == "plane-strain":
        s = math.sqrt(3 + ss * ss)
        return 3 * sp * s / (3 + sp * ss), 3 * ss / s, 3 * cp * s / (3 + sp * ss)
    raise ValueError(f"cone match '{match}': expected triaxial-compression or plane-strain")


def biaxial_response(material, confinement, axial_strain_end, steps=4000):
    """Homogeneous plane-strain biaxial test, compression negative.

    material: the resolved block of summary.json (lambda, mu [Pa]; viscoplasticity with angles
    in degrees, cohesion, hardening, residual_cohesion [Pa], cone_match).
    Returns arrays (axial strain eps_yy, axial stress sigma_yy, sigma_zz, ebar)."""
    lam, mu = float(material["lambda"]), float(material["mu"])
    vp = material["viscoplasticity"]
    m_phi, m_psi, kc = cone_coefficients(float(vp["friction_angle"]), float(vp["dilatancy_angle"]),
                                         vp["cone_match"])
    c0, h = float(vp["cohesion"]), float(vp["hardening"])
    c_res = float(vp["residual_cohesion"])
    bulk = lam + 2 * mu / 3

    def update(strain, plastic, ebar):
        """Stress and state after the return from (strain, plastic strain, ebar) at step start."""
        elastic = strain - plastic
        sigma = lam * elastic.sum() + 2 * mu * elastic
        p = sigma.mean()
        s = sigma - p
        q = math.sqrt(1.5 * s @ s)
        c = max(c0 + h * ebar, c_res)
        f = q + m_phi * p - kc * c
        if f <= 0 or q == 0:
            return sigma, plastic, ebar
        slope = kc * h if c0 + h * ebar > c_res else 0.0
        dgamma = f / (3 * mu + m_phi * bulk * m_psi + slope)  # linear: q, p, c are linear in dgamma
        plastic = plastic + dgamma * (1.5 * s / q + m_psi / 3)
        elastic = strain - plastic
        return lam * elastic.sum() + 2 * mu * elastic, plastic, ebar + dgamma

    plastic, ebar, exx = np.zeros(3), 0.0, 0.0
    rows = []
    for i in range(steps + 1):
        eyy = axial_strain_end * i / steps
        for _ in range(60):  # secant Newton on eps_xx for sigma_xx = -confinement
            sigma = update(np.array([exx, eyy, 0.0]), plastic, ebar)[0]
            residual = sigma[0] + confinement
            if abs(residual) < 1e-6 * max(confinement, 1.0):
                break
            probe = update(np.array([exx + 1e-9, eyy, 0.0]), plastic, ebar)[0]
            exx -= residual / ((probe[0] - sigma[0]) / 1e-9)
        sigma, plastic, ebar = update(np.array([exx, eyy, 0.0]), plastic, ebar)
        rows.append((eyy, sigma[1], sigma[2], ebar))
    return tuple(np.array(column) for column in zip(*rows))


def homogeneous_peak(material, confinement, height, travel_per_platen):
    """Peak of the homogeneous response within twice the given platen travel.

    Returns (peak axial stress magnitude [Pa], platen displacement at the peak [m] or None if
    the response still rises at twice the travel, axial stress magnitude at the case's travel)."""
    strain_end = -2.0 * (2.0 * travel_per_platen) / height  # twice the case's shortening
    eyy, syy, _, _ = biaxial_response(material, confinement, strain_end)
    k = int(np.argmin(syy))
    at_travel = float(np.interp(2.0 * travel_per_platen / height, -eyy, -syy))
    peak_displacement = None if k == len(eyy) - 1 else float(-eyy[k] * height / 2.0)
    return float(-syy[k]), peak_displacement, at_travel
