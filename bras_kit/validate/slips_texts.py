"""The English words of the slips rules (BK214, BK509; BK100's comment wording is in ``texts``).
French: ``locale/fr/LC_MESSAGES/validate.po`` (msgctxt = the rule code)."""

from __future__ import annotations

from ..findings.registry import describe

describe(
    "BK214",
    title="an rpy written in degrees",
    message={
        "joint": "joint '{owner}': rpy=\"{rpy}\" turns by {angle} radians (so by {effective} degrees): URDF "
        "angles are radians, and {angle} reads as degrees",
        "": "link '{owner}': rpy=\"{rpy}\" turns by {angle} radians (so by {effective} degrees): URDF "
        "angles are radians, and {angle} reads as degrees",
    },
    hint="write the angles in radians: {origin}",
    explanation="""\
Every angle in a URDF is in radians: `rpy="0 1.5708 0"` is a quarter turn about y. Written
`rpy="0 90 0"`, the part turns by 90 radians, that is 14 whole turns and 117 degrees: RViz draws
it turned by 117 degrees, which looks like a drawing error rather than a unit. bras-kit reports an angle
past a full turn that is a whole number: nobody means 90 radians. Convert with
radians = degrees x pi / 180 (90 -> 1.5708, 45 -> 0.7854, 180 -> 3.1416).""",
)
describe(
    "BK509",
    title="a mass written in grams",
    message="link '{link}' weighs {mass} kg for its {shape}: {density} kg/m3, denser than any solid; "
    "a mass in grams would be {kilograms} kg",
    hint="URDF masses are kilograms: write <mass value=\"{kilograms}\"/> if {mass} was grams",
    explanation="""\
`<mass value>` is in kilograms. For a mass of 10 kg or more, bras-kit divides it by the volume of
the link's one primitive shape: past 30,000 kg/m3 no material explains it (osmium, the densest, is 22,590),
while the same number read as grams gives a plausible solid. A 500 g forearm written 500 is half
a tonne: RViz does not care, a simulation sags or explodes under it. A warning, since a link's
drawn shape may be only part of the real body.""",
)
