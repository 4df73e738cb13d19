"""A body to toss for the synthetic recordings (issue 40, item 4): a phone's drag plate and a flat
plate's drag coefficient by default, a box from its mass and sides, and bodies that are none refused."""

from __future__ import annotations

import numpy as np
import pytest

from tumble.analysis.fit.synthetic import TOSS_BODIES, TossBody, plate_drag_torque, synthetic_recording
from tumble.analysis.fit.tossbody import PHONE_SIZE, PLATE_DRAG_COEFFICIENT, RHO_AIR


def test_a_body_given_its_moments_alone_has_a_phones_plate():
    mine = TossBody("mine", (2.4e-4, 4.0e-4, 6.3e-4))
    assert (mine.length, mine.width) == PHONE_SIZE == (TOSS_BODIES["phone"].length, TOSS_BODIES["phone"].width)
    assert mine.drag_coefficient == PLATE_DRAG_COEFFICIENT == TOSS_BODIES["phone"].drag_coefficient
    # strip theory about the width's axis: rho C_D W L^4 / 64 w^2 (the synthetic module's docstring)
    w = 10.0
    L, W = PHONE_SIZE
    closed = RHO_AIR * PLATE_DRAG_COEFFICIENT * W * L ** 4 / 64 * w * w
    assert plate_drag_torque(mine, np.array([0.0, w, 0.0]))[1] == pytest.approx(-closed, rel=2e-2)
    rec = synthetic_recording(3, body=mine, tosses=2)
    np.testing.assert_allclose(rec.ratios, [2.4 / 6.3, 4.0 / 6.3])
    assert rec.body == mine


def test_a_box_is_its_mass_and_sides_with_its_largest_face_the_plate():
    m, a, b, c = 0.6, 0.24, 0.17, 0.03
    book = TossBody.box("book", m, a, b, c)
    np.testing.assert_allclose(book.moments, np.array([b * b + c * c, a * a + c * c, a * a + b * b]) * m / 12)
    assert (book.length, book.width, book.drag_coefficient) == (a, b, PLATE_DRAG_COEFFICIENT)
    assert TossBody.box("phone", 0.19, *PHONE_SIZE, 0.008) == TOSS_BODIES["phone"]
    with pytest.raises(ValueError, match="sides"):
        TossBody.box("wrong way", m, c, b, a)


@pytest.mark.parametrize("kwargs, words", [
    ({"moments": (3e-4, 2e-4, 1e-4)}, "ascending"),
    ({"moments": (0.0, 2e-4, 3e-4)}, "positive principal moments"),
    ({"moments": (1e-4, 2e-4)}, "three positive"),
    ({"length": -0.1}, "length = -0.1 must be a positive length"),
    ({"width": float("nan")}, "width = nan"),
    ({"drag_coefficient": -1.0}, "drag_coefficient = -1.0 must be >= 0"),
])
def test_a_body_that_is_none_is_refused_naming_the_value(kwargs, words):
    given = {"name": "x", "moments": (1e-4, 2e-4, 3e-4), **kwargs}
    with pytest.raises(ValueError, match=words):
        TossBody(**given)


def test_no_air_is_a_coefficient_of_zero():
    still = TossBody("still", (1e-4, 2e-4, 3e-4), drag_coefficient=0.0)
    assert not plate_drag_torque(still, np.array([3.0, 5.0, 7.0])).any()
