"""The English words of the Gazebo rules (BK7xx). French: ``locale/fr/LC_MESSAGES/validate.po``
(msgctxt = the rule code)."""

from __future__ import annotations

from ..findings.registry import Plural, describe

describe(
    "BK700",
    title="a link and a joint share a name",
    message="'{shared}' names both a link (line {link_line}) and a joint (line {joint_line}): RViz accepts it, "
    "Gazebo refuses the model (\"Joint with non-unique name [{shared}]\")",
    hint="rename the link, e.g. '{rename}', in its <link> and in the <parent>/<child> that name it: the joint "
    "keeps the name that motions, /joint_states and launch files use",
    explanation="""\
urdfdom, which RViz and robot_state_publisher use, keeps links and joints in two separate lists,
so a link and a joint may share a name (the tutorial's hint writes both as `poignet`). Gazebo
converts the URDF to SDF, where links, joints and frames share one namespace: libsdformat then
refuses the whole model ("Joint with non-unique name", followed by frame-graph cycles) and
nothing appears in the simulator. Give the two different names: bras-kit's own wrist keeps the
joint `poignet`, which the learner moves and sees in /joint_states, and names the segment it
moves `main` (the hand), as `epaule` moves `bras`.""",
)
describe(
    "BK701",
    title="no link has an <inertial>: Gazebo would load nothing",
    message=Plural(
        "no link has an <inertial>: Gazebo would not load this {count} link (\"A model must have at least one link\")",
        "no link has an <inertial>: Gazebo would load none of the {count} links (\"A model must have at least one link\")",
        "count"),
    hint="fine for RViz; before Gazebo, give every link an <inertial> (bras-kit urdf --inertials shows one)",
    explanation="""\
Gazebo's URDF reader (libsdformat) does not model a link without `<inertial>`, nor anything
below it. The tutorial's arm has none, which is right for RViz (BK505 notes it): bras-kit says
this only with `bras-kit validate --target gazebo`, as an error. The tutorial's exercise "ajouter des
`<inertial>`" is the preliminary to simulation; `bras-kit gazebo` shows what Gazebo keeps.""",
)
describe(
    "BK702",
    title="a link without <inertial> is dropped by Gazebo, with everything below it",
    message={
        "": "link '{link}' has no <inertial> while other links have one: Gazebo drops it without a word",
        "below": "link '{link}' has no <inertial> while other links have one: Gazebo drops it and all "
        "that hangs below it ({below}; joints {joints}) without a word",
        "empty": "root link '{link}' has no <inertial>: Gazebo drops it and every link below it, leaving an empty "
        "model (\"A model must have at least one link\")",
        "merged": "frame link '{link}' has no <inertial>: Gazebo merges it into '{into}' but drops all "
        "that hangs below it ({below}; joints {joints})",
    },
    hint={
        "": "add an <inertial> with a positive <mass> to '{link}' (bras-kit urdf --inertials shows one)",
        "merged": "add an <inertial> with a small positive <mass> to '{link}', or hang its children from '{into}'",
    },
    explanation="""\
libsdformat's URDF conversion (`CreateSDF` in parser_urdf.cc) stops at a link whose
`<inertial>`, after merging the links fixed to it, is missing: it does not model that link,
nor any link below it, nor their joints, and `ign sdf -k` still says "Valid.". The arm in
Gazebo then ends at the forgotten link (the "dismembered wrist"). A warning, since the other
links show the job was started; an error with `--target gazebo`. A root link without
`<inertial>` empties the model. A frame link on a fixed joint (a flange) is merged into its
parent, but the walk still stops there, so a gripper hanging from it by a moving joint is lost.""",
)
describe(
    "BK703",
    title="a mass of at most 1e-6 kg: Gazebo drops the link",
    message={
        "": "link '{link}' weighs {mass:g} kg: Gazebo treats a mass of at most 1e-6 kg as none and drops the link",
        "below": "link '{link}' weighs {mass:g} kg: Gazebo treats a mass of at most 1e-6 kg as none and drops it "
        "with all that hangs below it ({below})",
        "empty": "root link '{link}' weighs {mass:g} kg: Gazebo drops it and every link below it, leaving an empty "
        "model",
        "merged": "frame link '{link}' weighs {mass:g} kg: Gazebo merges it into '{into}' but drops all "
        "that hangs below it ({below})",
    },
    hint="give '{link}' its real mass (more than 1e-6 kg), or remove its <inertial> if it is a mere frame "
    "fixed to its parent",
    explanation="""\
libsdformat compares the mass with zero within 1e-6 (`ignition::math::equal(mass, 0.0)`), so a
placeholder mass of 1e-6 or less counts as no `<inertial>` at all: the link, what hangs below it
and their joints are not modelled, silently. A mass of 1e-5 kg is kept.""",
)
describe(
    "BK704",
    title="links on fixed joints are merged: their frames disappear in Gazebo",
    message={
        "one": "Gazebo merges link '{link}' into '{into}' (fixed joint '{joint}'): the frame '{link}' does not "
        "exist in the simulation",
        "": Plural(
            "Gazebo merges {count} link on a fixed joint into its parent ({frames}): that frame does not exist in the simulation",
            "Gazebo merges {count} links on fixed joints into their parents ({frames}): those frames do not exist in the simulation",
            "count"),
    },
    hint='to keep a frame (a TCP, a camera mount), add <gazebo reference="{joint}"><preserveFixedJoint>true'
    "</preserveFixedJoint></gazebo>, and give the link an <inertial> of its own (kept, it is a link like any other)",
    explanation="""\
libsdformat lumps a link hanging from a `fixed` joint into its parent (`ReduceFixedJoints`):
its visuals, collisions and mass move into the parent and its frame is gone, so a plugin, a
sensor or a pose request that names it finds nothing. `<gazebo reference="JOINT">
<preserveFixedJoint>true</preserveFixedJoint></gazebo>` keeps the joint and its link (the
older `<disableFixedJointLumping>` keeps it too, as a revolute joint locked at 0). A link kept
this way is modelled like any other, so it needs an `<inertial>` with a positive mass, or it is
dropped (BK702). Said with `--target gazebo` only, as a warning: the bodies are all there.""",
)
describe(
    "BK705",
    title="nothing fixes the robot to the world: it falls over in Gazebo",
    message="root link '{link}' is not fixed to the world: Gazebo spawns a free body, and an arm falls over",
    hint='for an arm bolted to a table, add <link name="world"/> and a fixed joint from world to \'{link}\'',
    explanation="""\
RViz draws the root link where the fixed frame says; Gazebo simulates it, with gravity. A
URDF whose root is a link named `world` is fixed to the ground (libsdformat writes its joint
relative to the world); any other root is a free body, right for a mobile robot, wrong for
the tutorial's arm, which topples as soon as it moves. Said with `--target gazebo` only, as a
warning.""",
)
describe(
    "BK706",
    title="a moving link has no <collision>: it falls through the floor and the other links",
    message={
        "one": "link '{link}' moves but has no <collision>: in Gazebo it passes through the floor and the other "
        "links",
        "": Plural(
            "{count} moving link has no <collision> ({links}): in Gazebo it passes through the floor and the other links",
            "{count} moving links have no <collision> ({links}): in Gazebo they pass through the floor and the other links",
            "count"),
    },
    hint="give '{link}' a <collision> (the same <geometry> and <origin> as its <visual> is a good start)",
    explanation="""\
RViz only draws `<visual>`; Gazebo's contacts use `<collision>` alone. A link without one,
after merging the links fixed to it, touches nothing. Said with `--target gazebo` only, as a
warning.""",
)
describe(
    "BK707",
    title="package:// meshes become model:// in Gazebo",
    message="Gazebo reads '{filename}' as '{uri}' (packages: {packages}): it finds "
    "such meshes only through its resource path",
    hint="add the folder that holds '{package}' to IGN_GAZEBO_RESOURCE_PATH (Fortress) or GZ_SIM_RESOURCE_PATH "
    "(Harmonic), or install the package and launch through ros_gz",
    explanation="""\
libsdformat rewrites `package://P/...` to `model://P/...` (`CreateGeometry`). RViz resolves
`package://` through the ROS package index; Gazebo looks for a folder `P` on its resource path,
so a mesh that shows in RViz may be missing in Gazebo (the robot then appears without its
shapes). Said with `--target gazebo` only, as a warning.""",
)
describe(
    "BK708",
    title="colours Gazebo cannot show: a component above 0.8 saturates",
    message="Gazebo shows material '{material}' rgba {rgba} as {gazebo}: it divides red, green and blue by 0.8 "
    "and caps them at 1, so it cannot show these colours ({saturated})",
    hint="keep r, g and b at 0.8 or below (Gazebo shows rgba/0.8), or give <gazebo reference=\"LINK\"> a "
    "<visual><material> with <diffuse> and <ambient>",
    explanation="""\
libsdformat turns a URDF `<color rgba>` into an SDF diffuse and ambient colour of r/0.8, g/0.8,
b/0.8, capped at 1 (the alpha is kept; `CreateVisual` in parser_urdf.cc): every colour comes out
brighter, and a component above 0.8 saturates, so Gazebo does not show the colour written and two
colours may become one. Textures are not converted. `bras-kit gazebo -o` draws the colours as
Gazebo shows them. Said with `--target gazebo` only, as a note.""",
)
describe(
    "BK709",
    title="a floating or planar joint has no Gazebo counterpart",
    message="joint '{joint}' is {type}: libsdformat writes link '{link}' without it, posed relative to a joint "
    "that does not exist, and refuses the model",
    hint="for a mobile base, drop the joint and let '{link}' be the root; otherwise use a fixed, revolute or "
    "prismatic joint",
    explanation="""\
SDF has no floating or planar joint; libsdformat's conversion writes no joint for them but
still poses the child link relative to the joint's name, and the check fails on the missing
frame. A warning; an error with `--target gazebo`.""",
)
describe(
    "BK710",
    title="a zero mass merged into a link without mass: Gazebo's centre of mass is NaN",
    message="link '{link}': merging the fixed links into it adds 0 kg to 0 kg, libsdformat divides by zero and "
    "the centre of mass becomes NaN: Gazebo refuses the model (\"Pose values must be finite\")",
    hint="remove the <inertial> with mass 0 from the frame links fixed to '{link}' (a frame needs none)",
    explanation="""\
When libsdformat merges a fixed link into its parent it averages their centres of mass, weighted
by mass (`dMassAdd`). If the first link merged into a link without mass has an `<inertial>` of
mass 0, the average is 0/0: NaN, which nothing later undoes. The model is then refused. A
frame link (a camera's optical frame) needs no `<inertial>`; without one it is merged cleanly.""",
)
describe(
    "BK711",
    title="Gazebo refuses a link's inertia",
    message={
        "": "link '{link}': Gazebo refuses its inertia (\"A link named {link} has invalid inertia\"): a negative "
        "mass or moment, or principal moments A + B < C",
        "merged": "link '{link}': Gazebo refuses its inertia once the fixed links {merged} are merged into it "
        "(\"A link named {link} has invalid inertia\")",
    },
    hint={
        "": "recompute the <inertia> of '{link}' from its shape and mass (for a box: ixx = m (y\u00b2 + z\u00b2) / 12, ...)",
        "merged": "check the <inertial> of '{link}' and of {merged}: each must be a real body's, in its own <origin>",
    },
    explanation="""\
Gazebo checks each link's inertia with ignition-math's `MassMatrix3::IsValid`: the mass and the
moments must not be negative and the principal moments must satisfy A + B >= C, within about
1e-15 of their sum. It checks the inertia libsdformat wrote, that is the link's own plus those
of the links merged into it through fixed joints, so a link whose own `<inertial>` is right can
still be refused. The whole model is then refused. BK501, BK502 and BK507 judge each link as
written; this rule says what Gazebo does with the merged body.""",
)
