"""Newton's failure criterion at the minimum damping: a corrector that cycles between the sides of
a kink gives up after its second damped step at ``lambda_min`` instead of spending its whole budget;
a run that converges is untouched by the option."""
import numpy as np

from ringdamper.nonlinear.newton import newton


def kink_without_root(z, jacobian):
    """``r = |z| + 1`` (no root) with the one-sided Jacobian ``sign(z)`` (+1 at 0): every Newton
    direction points across the kink at 0, where the residual grows again."""
    J = np.diag(np.where(z >= 0, 1.0, -1.0)) if jacobian else None
    return np.abs(z) + 1.0, J, None, 1, None


def arctan(z, jacobian):
    """``r = arctan z``: plain Newton diverges from |z| > 1.39, the damped steps converge."""
    return np.arctan(z), (np.diag(1.0 / (1.0 + z**2)) if jacobian else None), None, 1, None


def unit_scale(z):
    return np.ones_like(z)


def test_cycling_newton_gives_up_at_its_second_minimum_damping():
    for start, jacobians in ((1.0, 3), (0.0, 2)):         # from 1: a step of 1/2 first, then two at 1/256
        given = newton(kink_without_root, np.array([start]), unit_scale, 1e-10, 20,
                       give_up_at_min_damping=True)
        assert not given.converged and "damping at its minimum" in given.reason
        assert given.jacobians == jacobians
        spent = newton(kink_without_root, np.array([start]), unit_scale, 1e-10, 20)
        assert not spent.converged and spent.jacobians > 20          # the whole budget


def test_converging_newton_is_untouched_by_the_option():
    for start in (0.5, 3.0):                                  # undamped, and damped steps
        plain = newton(arctan, np.array([start]), unit_scale, 1e-12, 20)
        given = newton(arctan, np.array([start]), unit_scale, 1e-12, 20, give_up_at_min_damping=True)
        assert plain.converged and given.converged and abs(plain.z[0]) < 1e-11
        assert np.array_equal(plain.z, given.z) and plain.jacobians == given.jacobians
        assert plain.iterations == given.iterations
