"""doctor --ros and view --ros on the generated live states (tests/live_states.py): one verdict each,
the one the category's flaw calls for, and the same on both sides (issue 56)."""

from __future__ import annotations

import pytest
from live_states import HELD_OUT, generate
from live_verdicts import judge

NAMES = [s.name for s in generate() if s.name not in HELD_OUT]


@pytest.mark.parametrize("name", NAMES)
def test_doctor_and_view_give_the_category_s_verdict(name):
    # made now: view --ros judges the seconds before its clock
    state = next(s for s in generate() if s.name == name)
    assert judge(state) == []


def test_every_category_has_several_states():
    by_category: dict[str, int] = {}
    for state in generate():
        by_category[state.category] = by_category.get(state.category, 0) + 1
    assert len(by_category) >= 11 and min(by_category.values()) >= 2
    assert sum(by_category.values()) >= 40
