"""The generated live states kept aside while the rules were fixed (tests/live_states.py HELD_OUT),
run last: their verdicts were not looked at before."""

from __future__ import annotations

import pytest
from live_states import HELD_OUT, generate
from live_verdicts import judge

NAMES = [s.name for s in generate() if s.name in HELD_OUT]


@pytest.mark.parametrize("name", NAMES)
def test_held_out_states_get_the_category_s_verdict(name):
    # made now: view --ros judges the seconds before its clock
    state = next(s for s in generate() if s.name == name)
    assert judge(state) == []
