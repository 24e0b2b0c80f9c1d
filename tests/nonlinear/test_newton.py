"""Newton's failure criterion at a raised damping floor: a corrector that cycles between the sides of
a kink gives up at its first damped step that needs ``λ <= give_up_damping`` instead of spending its
whole budget; a run whose damped steps stay above the floor is untouched by the option."""
import numpy as np

from ringdamper.nonlinear.solvers.jacobian import Evaluation
from ringdamper.nonlinear.solvers.newton import newton


def kink_without_root(z, jacobian):
    """``r = |z| + 1`` (no root) with the one-sided Jacobian ``sign(z)`` (+1 at 0): every Newton
    direction points across the kink at 0, where the residual grows again."""
    J = np.diag(np.where(z >= 0, 1.0, -1.0)) if jacobian else None
    return Evaluation(np.abs(z) + 1.0, J, None, 1, None)


def arctan(z, jacobian):
    """``r = arctan z``: plain Newton diverges from |z| > 1.39, the damped steps converge."""
    return Evaluation(np.arctan(z), (np.diag(1.0 / (1.0 + z**2)) if jacobian else None), None, 1, None)


def unit_scale(z):
    return np.ones_like(z)


FLOOR = 1.0 / 16


def test_cycling_newton_gives_up_at_its_first_step_below_the_floor():
    for start, jacobians in ((1.0, 2), (0.0, 1)):         # from 1: a step of 1/2 first, then one at 1/16
        given = newton(kink_without_root, np.array([start]), unit_scale, 1e-10, 20, give_up_damping=FLOOR)
        assert not given.converged and "outside Newton's contraction" in given.reason
        assert given.jacobians == jacobians
        spent = newton(kink_without_root, np.array([start]), unit_scale, 1e-10, 20)
        assert not spent.converged and spent.jacobians > 20          # the whole budget


def test_converging_newton_is_untouched_by_the_option():
    for start in (0.5, 3.0):                                  # undamped, and a first step damped to 1/4
        plain = newton(arctan, np.array([start]), unit_scale, 1e-12, 20)
        given = newton(arctan, np.array([start]), unit_scale, 1e-12, 20, give_up_damping=FLOOR)
        assert plain.converged and given.converged and abs(plain.z[0]) < 1e-11
        assert np.array_equal(plain.z, given.z) and plain.jacobians == given.jacobians
        assert plain.iterations == given.iterations


def shelf(z, jacobian):
    """``r = z`` above ``z = 1/2`` and a shelf of slope 1/100 below it (root at −49.5): from z = 1 a
    full step lands on the shelf, where the chord steps stall and the fresh Jacobian's correction is
    49 times the first one's."""
    low = z < 0.5
    r = np.where(low, 0.5 + 0.01 * (z - 0.5), z)
    return Evaluation(r, (np.diag(np.where(low, 0.01, 1.0)) if jacobian else None), None, 1, None)


def test_a_corrector_whose_newton_correction_grows_between_jacobians_fails():
    given = newton(shelf, np.array([1.0]), unit_scale, 1e-10, 20, give_up_damping=FLOOR)
    assert not given.converged and given.jacobians == 2
    assert "Newton correction grew from 1 to 49" in given.reason
    spent = newton(shelf, np.array([1.0]), unit_scale, 1e-10, 20)     # the start point and the grid solves
    assert spent.converged and abs(spent.z[0] + 49.5) < 1e-9
