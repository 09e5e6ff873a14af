# SPDX-License-Identifier: GPL-3.0-or-later
"""What the plot scripts in tools/ share: units of scene keys for axis labels, legends placed
outside the curves, and axes that draw a flat signal flat.

Needs matplotlib only through the axes passed in; importing this module needs nothing.
"""
import math

#: The unit of a scene key, by its last dotted part (docs/SCENES.md gives each key's unit).
#: "-" marks a dimensionless key.
KEY_UNITS = {
    "velocity": "m/s", "angular_velocity": "rad/s", "position": "m", "rotation": "deg",
    "point": "m", "gravity": "m/s²", "mass": "kg",
    "end_time": "s", "time_step": "s", "output_interval": "s", "history_interval": "s",
    "checkpoint_interval": "s", "checkpoint_wall_interval": "s", "mass_scaling_time_step": "s",
    "rest_hold_time": "s",
    "density": "kg/m³", "youngs_modulus": "Pa", "poisson_ratio": "-", "yield_stress": "Pa",
    "hardening_modulus": "Pa", "cohesion": "Pa", "residual_cohesion": "Pa",
    "cohesion_hardening_modulus": "Pa", "friction_angle": "deg", "dilatancy_angle": "deg",
    "dilatancy": "-", "rate_coefficient": "-", "reference_strain_rate": "1/s",
    "element_size": "m", "radius": "m", "length": "m", "size": "m", "refine_size": "m",
    "refine_radius": "m", "refine_point": "m", "refine_growth": "-", "cells_per_radius": "-",
    "diameter": "m", "diameter_mean": "m", "height": "m", "count": "-", "seed": "-",
    "friction": "-", "penalty_factor": "-", "damping": "-", "impact_damping": "-",
    "deformation_damping": "-", "time_step_safety": "-", "mass_scaling_limit": "-",
    "rest_kinetic_fraction": "-", "energy_balance_limit": "-", "initial_overlap": "-",
    "scale": "-", "die_area": "m²", "die_perimeter": "m", "fit_min_pressure": "Pa",
    "fit_max_pressure": "Pa",
}


def key_unit(key):
    """The unit of a dotted scene key ("bodies.ball.velocity" -> "m/s"), "-" for a
    dimensionless one, None when the key is not known. An array component ("velocity[2]")
    has the array's unit."""
    last = key.split(".")[-1].split("[")[0]
    return KEY_UNITS.get(last)


def key_label(key):
    """An axis label for a scene key: "bodies.ball.velocity[2] [m/s]"; a dimensionless key
    gets "[-]", an unknown one no unit."""
    unit = key_unit(key)
    return f"{key} [{unit}]" if unit else key


def legend_outside(ax, **kwargs):
    """The axes' legend to the right of the plot, where it cannot cover a curve (the figure
    must leave room: fig.tight_layout() does when called after this). No legend when nothing
    is labelled."""
    handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return None
    options = {"loc": "upper left", "bbox_to_anchor": (1.02, 1.0), "borderaxespad": 0.0,
               "fontsize": 8}
    options.update(kwargs)
    return ax.legend(handles, labels, **options)


#: A signal whose range is below this fraction of its scale is drawn flat.
FLAT_FRACTION = 1e-6
#: The y span of the axes then, as a fraction of the scale.
FLAT_SPAN_FRACTION = 1e-3


def draw_flat_flat(ax, values, scale=None):
    """Keeps round-off from being magnified into a signal: when the plotted values (an iterable
    of sequences) vary by less than FLAT_FRACTION of `scale` (default: the largest |value|, or
    1 when every value is 0), the y axis spans FLAT_SPAN_FRACTION of the scale around their
    middle, without offset notation, so the curve is drawn as the flat line it is. A signal that
    really varies keeps matplotlib's limits. Returns True when the axis was fixed."""
    lo, hi = math.inf, -math.inf
    for series in values:
        for v in series:
            v = float(v)
            if math.isfinite(v):
                lo, hi = min(lo, v), max(hi, v)
    if lo > hi:
        return False
    if scale is None or not (scale > 0.0):
        scale = max(abs(lo), abs(hi))
    if not (scale > 0.0):
        scale = 1.0
    if hi - lo > FLAT_FRACTION * scale:
        return False
    mid = 0.5 * (lo + hi)
    half = 0.5 * FLAT_SPAN_FRACTION * scale
    ax.set_ylim(mid - half, mid + half)
    ax.ticklabel_format(axis="y", useOffset=False)
    return True
