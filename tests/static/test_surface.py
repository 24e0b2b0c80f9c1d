"""Pair positions on the ring's upper surface (ringdamper.static.surface) against pairs placed at known
radius r, angle θ and axial position z: s = r θ, z, and |θ| / θ_h."""
import numpy as np
import xarray as xr

from ringdamper.static.surface import sector_position, surface_coords

HALF_ANGLE = np.pi / 24


def pairs(r, theta, z):
    return xr.Dataset({"x": ("pair", r * np.cos(theta)), "y": ("pair", r * np.sin(theta)), "z": ("pair", z)})


def test_arc_and_axial_positions_of_known_pairs():
    theta = np.linspace(-HALF_ANGLE, HALF_ANGLE, 7)
    r, z = np.full(7, 0.1625), np.linspace(0.011, 0.017, 7)
    s, z_out = surface_coords(pairs(r, theta, z))
    np.testing.assert_allclose(s, r * theta, rtol=1e-13, atol=1e-17)
    assert np.array_equal(z_out, z)


def test_sector_position_runs_from_the_centre_to_the_boundaries():
    theta = np.array([0.0, HALF_ANGLE / 3, -2 * HALF_ANGLE / 3, HALF_ANGLE, -HALF_ANGLE])
    position = sector_position(pairs(np.full(5, 0.16), theta, np.zeros(5)), HALF_ANGLE)
    np.testing.assert_allclose(position, [0.0, 1 / 3, 2 / 3, 1.0, 1.0], rtol=1e-13, atol=1e-15)
