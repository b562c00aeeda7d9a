"""The English words of the URDF and xacro rules (BK1xx-BK5xx): title, message, hint and the
explanation ``bras-kit explain CODE`` shows. French: ``locale/fr/LC_MESSAGES/validate.po``
(msgctxt = the rule code)."""

from __future__ import annotations

from ..findings.registry import Plural, describe

# ------------------------------------------------------------------ BK1xx structure

describe(
    "BK100",
    title="the file is not well-formed XML",
    message={
        "": "not well-formed XML: {detail}",
        "encoding": "the file is not UTF-8 text: byte {byte} on line {at} would be '{guess}' in Latin-1, so the file was probably saved as Latin-1 or Windows-1252",
        "comment": "the comment opened on line {line} ends with '->' on line {arrow_line}, not '-->': it runs on to the '-->' of line {end_line} and hides {hidden}, which check_urdf reports missing",
        "comment_unclosed": "the comment opened on line {line} ends with '->' on line {arrow_line}, not '-->': no '-->' follows, so it runs to the end of the file and hides {hidden}",
        "pasted": "not well-formed XML: {detail}",
    },
    hint={
        "": "look at this line: a tag left open, a missing '/>' or a stray quote are the usual causes",
        "pasted": "{fix}, then check the file again",
        "encoding": 're-save the file as UTF-8 in your editor (or declare its encoding: <?xml version="1.0" encoding="ISO-8859-1"?>)',
        "comment": "close the comment on line {arrow_line} with '-->' (two dashes)",
        "comment_unclosed": "close the comment on line {arrow_line} with '-->' (two dashes)",
    },
    explanation="""\
The file could not be read as XML, so nothing else in it was checked. The line given is where
the XML reader gave up; the mistake is often on that line or just above it: a tag that is never
closed, `<box size="...">` written without its `/`, a quote opened and not closed, or an `&`
that should be written `&amp;`.

This is an input failure: `bras-kit validate` reports it as a finding (so editors and CI see the
line) and exits with status 2, like any input it cannot read.""",
)
describe(
    "BK101",
    title="unsafe XML refused (DTD or entity)",
    message={
        "dtd": "refused: the file declares a DTD (<!DOCTYPE ...>){where}",
        "entity": "refused: the file declares an entity (<!ENTITY ...>){where}",
        "external": "refused: the file refers to an external entity{where}",
        "undefined": "refused: the file uses an entity reference (&name;) that bras-kit does not expand{where}",
        "": "refused: the file uses a DTD or an entity{where}",
    },
    hint={
        "undefined": "write the character itself instead of the &name; reference",
        "": "delete the <!DOCTYPE ...> block: URDF files never need one",
    },
    explanation="""\
A DTD or an entity declaration lets an XML file pull in other files or expand a few bytes into
gigabytes ("billion laughs"). URDF never needs either, so bras-kit refuses such files before
reading anything they point to: no file is opened, no URL fetched.

Remove the `<!DOCTYPE ...>` block and write plain text instead of `&name;` references. Like any
unreadable input, this finding makes `bras-kit validate` exit with status 2.""",
)
describe(
    "BK102",
    title="xacro could not expand the file",
    message="xacro failed: {detail}",
    hint={
        "arg": "give the argument on the command line (--xacro-arg name:=value) or a default in <xacro:arg>",
        "property": "define the property with <xacro:property name=... value=...> before it is used",
        "property_close": "did you mean '{close}'? Otherwise define the property with <xacro:property name=... value=...> before it is used",
        "include": "check the path of the included file: relative paths start from the including file",
        "package": "tell bras-kit where the package is: --package-path DIR or BRAS_KIT_PACKAGE_PATH",
        "unsafe": "xacro expressions may only compute numbers and strings from properties",
        "xml": "look at this line: a tag left open or a stray quote",
        "": "check the xacro syntax around this line",
    },
    explanation="""\
A `.xacro` file is expanded with the real xacro package before it is checked. When expansion
fails (an undefined property or argument, a missing include, a `$(find pkg)` for a package that
cannot be found, an expression bras-kit refuses to evaluate), nothing else can be checked.

`$(find pkg)` looks in `--package-path` folders and `BRAS_KIT_PACKAGE_PATH`, then in ROS's own
variables. Expressions that could run code (imports, dunder names, huge powers) are refused.
This finding makes `bras-kit validate` exit with status 2.""",
)
describe(
    "BK103",
    title="the file cannot be read",
    message={
        "missing": "no such file: {path}",
        "near": "no such file: {path}",
        "windows": "no such file: {path} (its '\\' separators are Windows's: on Linux and macOS they are part of the file's name)",
        "folder": "{path} is a folder, not a file",
        "": "cannot read {path}: {detail}",
    },
    hint={
        "missing": "check the path and its spelling",
        "near": "did you mean {suggestion}? It is in the same folder",
        "windows": "write the path with '/': {suggestion}",
        "folder": "give the folder itself to bras-kit validate: it checks the .urdf and .xacro files inside",
        "": "check the file exists and you may read it",
    },
    explanation="""\
The path given to `bras-kit validate` does not exist, is not readable, or is a folder where a
file was expected. Other paths on the same command line are still checked; the command then
exits with status 2 so that scripts notice.""",
)
describe(
    "BK125",
    title="the <?xml ?> declaration is not at the very start of the file",
    message={
        "": "the <?xml ...?> declaration is on line {at}, after blank lines or spaces: strict XML readers refuse the file",
        "tab": "the <?xml ...?> declaration on line {at} comes after a tab (U+0009), pasted with an indented listing: strict XML readers refuse the file",
    },
    hint={
        "": "delete the blank lines and spaces before <?xml",
        "tab": "delete the tab at the start of line {at}: <?xml must be the file's very first characters",
    },
    explanation="""\
XML allows nothing, not even a blank line, before the `<?xml version="1.0"?>` declaration.
urdfdom (`check_urdf`, robot_state_publisher) and pybullet read such a file anyway, so bras-kit
reads it too and checks the rest; but stricter tools (Python's XML parsers, some editors and
converters) refuse it. Remove whatever comes before `<?xml`.""",
)
describe(
    "BK126",
    title="a URDF generated from a xacro file beside it",
    message="this URDF was generated from {xacro}, which is checked instead; the two agree",
    hint="edit {xacro} and regenerate this file rather than editing it by hand",
    explanation="""\
A ROS 2 package often holds both `bras.urdf.xacro` and the `bras.urdf` made from it. When
`bras-kit validate` finds both in a folder it checks the xacro file only (every finding once,
at the line you would edit) and compares the URDF with a fresh expansion of the xacro.""",
)
describe(
    "BK127",
    title="a generated URDF no longer matches its xacro file",
    message="this URDF differs from what {xacro} gives now ({difference}): it is out of date",
    hint="keep one source: edit the file your launch file loads, or have the launch file run xacro on {xacro} "
         "(Command(['xacro ', path])) and stop installing {urdf}",
    explanation="""\
When a folder holds `bras.urdf.xacro` and `bras.urdf`, the URDF is taken as generated from the
xacro file. If the two disagree, the package installs and launches whichever file its launch
file names, so RViz may show an older robot than the one you edited. Regenerate the URDF (or
have the launch file run xacro itself).""",
)
describe(
    "BK124",
    title="xacro file with macros only",
    message="this xacro file defines macros but no link: it is a library, checked through the files that include it",
    hint="validate the top-level .xacro that includes this one",
    explanation="""\
ROS description packages often split a robot into a main `robot.urdf.xacro` and helper files
that only define `<xacro:macro>` blocks. Expanded alone, a helper file gives a robot with no
links, which would be an error (BK106) for a real robot file. When a `.xacro` expands to no link
and defines macros, bras-kit reports this note instead and checks nothing else in it.""",
)
describe(
    "BK104",
    title="the outer element is not <robot>",
    message="the outer element is <{tag}>, not <robot>",
    hint='a URDF file has one outer element, <robot name="...">, holding its links and joints',
    explanation="""\
Every URDF file has a single outer element, `<robot name="...">`; robot_state_publisher and
RViz refuse anything else. This often happens when a fragment of a larger file (a `<link>`
alone) or an SDF file (`<sdf>`) is given instead of a URDF.""",
)
describe(
    "BK105",
    title="the robot has no name",
    message="<robot> has no name attribute",
    hint='name the robot: <robot name="bras">',
    explanation="""\
The `name` attribute of `<robot>` is required: ROS's URDF parser stops with "No name given for
the robot" and robot_state_publisher never starts publishing. Any name will do.""",
)
describe(
    "BK106",
    title="the robot has no link",
    message="the robot has no <link>",
    hint='add at least one link, e.g. <link name="base"/>',
    explanation="""\
A robot is made of links (rigid parts) joined by joints. Without any `<link>` there is nothing
to publish and nothing to show. If this file is a xacro macro library, validate the file that
includes it instead.""",
)
describe(
    "BK107",
    title="two links with the same name",
    message="link '{link}' is defined twice (first on line {first_line})",
    hint="rename one of them: link names must be unique, and joints refer to links by name",
    explanation="""\
Joints refer to links by name, and TF publishes one frame per link name, so each name may be
used once. ROS's parser rejects a file with a repeated link name. Copy-pasting a link to make a
new segment (the tutorial's wrist exercise) and forgetting to rename it is the usual cause.""",
)
describe(
    "BK108",
    title="two joints with the same name",
    message="joint '{joint}' is defined twice (first on line {first_line})",
    hint="rename one of them: joint names must be unique (they are the names in /joint_states)",
    explanation="""\
Joint names are the keys of the `/joint_states` messages and of the sliders of
joint_state_publisher_gui, so each must be unique. ROS's parser rejects a repeated joint name.
A link and a joint may share a name (the tutorial's `poignet`), but two joints may not.""",
)
describe(
    "BK109",
    title="a top-level material is defined twice",
    message="material '{material}' is defined twice at the top level (first on line {first_line})",
    hint='keep one <material name="{material}"> at the top of the file, or rename the second',
    explanation="""\
Materials declared directly under `<robot>` are shared by name. Declaring the same name twice
there makes ROS's URDF parser fail with "material is not unique", so the robot is not loaded.""",
)
describe(
    "BK110",
    title="a material name is given two different colours",
    message="material '{material}' in link '{link}' has colour {colour}, but '{material}' is already {first_colour} (line {first_line}), which wins",
    hint="give this material its own name, or use the same colour in both places",
    explanation="""\
Materials are shared by name: the first definition of a name (top-level ones first) is the one
every visual using that name gets. A later `<material name="x">` with another colour is
silently ignored, so a segment shows in an unexpected colour. Use a distinct name per colour.""",
)
describe(
    "BK111",
    title="a joint's parent link does not exist",
    message="joint '{joint}' has parent link '{link}', which is not defined",
    hint={
        "close": "did you mean '{close}'? Link names must match exactly, case included",
        "": 'define <link name="{link}"> or use one of the links: {links}',
    },
    explanation="""\
`<parent link="...">` must name a link defined in the same file, spelled exactly the same
(case, underscores, accents). Otherwise the joint hangs in the void: ROS's parser fails and
robot_state_publisher publishes nothing.""",
)
describe(
    "BK112",
    title="a joint's child link does not exist",
    message="joint '{joint}' has child link '{link}', which is not defined",
    hint={
        "close": "did you mean '{close}'? Link names must match exactly, case included",
        "": 'define <link name="{link}"> or use one of the links: {links}',
    },
    explanation="""\
`<child link="...">` must name a link defined in the same file, spelled exactly the same.
A typo here leaves the intended link disconnected and makes ROS's parser fail.""",
)
describe(
    "BK113",
    title="a joint connects a link to itself",
    message="joint '{joint}' has '{link}' as both parent and child",
    hint="a joint connects two different links: the one it hangs from (parent) and the one it moves (child)",
    explanation="""\
A joint places a child link relative to a parent link; connecting a link to itself is a loop of
length one and has no meaning. Usually the child was copied from the parent line and not
changed.""",
)
describe(
    "BK114",
    title="a link has two parents",
    message="link '{link}' is the child of joint '{first_joint}' (line {first_line}) and again of joint '{joint}'",
    hint="each link hangs from exactly one joint: change the child of '{joint}' or remove it",
    explanation="""\
URDF describes a tree: every link except the root is the child of exactly one joint. A second
joint naming the same child would make the link's position ambiguous; ROS's parser rejects it
and TF cannot publish the frame. Closed chains (parallel mechanisms) cannot be written directly
in URDF.""",
)
describe(
    "BK115",
    title="the joints form a loop",
    message="the joints form a loop: {loop}",
    hint=Plural(
        "break the loop: the joint {joints} points back up the tree; make its child a new link",
        "break the loop: one of the joints {joints} points back up the tree; make its child a new link",
        "joints"),
    explanation="""\
Following parent links from child to parent must end at the root. Here it comes back to where
it started, so none of these links can be placed and no root can be found for them. Usually one
joint has its parent and child swapped.""",
)
describe(
    "BK116",
    title="several root links",
    message="the robot has several root links: {roots}",
    hint="attach '{extra}' under another link with a joint (for instance a fixed joint from '{root}')",
    explanation="""\
A URDF tree has exactly one root link, the one that is the child of no joint (in the tutorial,
`base`, which RViz's Fixed Frame is set to). With several roots, ROS's parser stops with "Two
root links found" and nothing is published. Connect each extra root with a joint.""",
)
describe(
    "BK117",
    title="a link is connected to nothing",
    message="link '{link}' is not connected by any joint",
    hint='add a joint with <child link="{link}"/>, for instance from \'{root}\', or remove the link',
    explanation="""\
Every link must be reached from the root through joints. A link that no joint mentions is a
second root: ROS's parser refuses the file, and RViz could not place the link anyway. It is
often a link added for the wrist exercise before its joint was written.""",
)
describe(
    "BK118",
    title="unknown joint type",
    message="joint '{joint}' has type '{type}', which URDF does not know",
    hint={
        "close": 'did you mean type="{close}"? Types are lower case',
        "": "use one of: {types}",
    },
    explanation="""\
URDF knows six joint types: `revolute` (turns, with stops), `continuous` (turns without stops),
`prismatic` (slides), `fixed`, `floating` and `planar`. Types are lower case; any other word
makes ROS's parser fail.""",
)
describe(
    "BK119",
    title="xacro markup left in a URDF file",
    message={
        "more": Plural(
            "xacro markup in a plain URDF: <{tag}> (and {more} more line)",
            "xacro markup in a plain URDF: <{tag}> (and {more} more lines)",
            "more"),
        "": "xacro markup in a plain URDF: <{tag}>",
    },
    hint="expand it first (bras-kit xacro {path} -o robot.urdf), or name the file .xacro so bras-kit expands it",
    explanation="""\
`<xacro:...>` elements and `${...}` / `$(...)` expressions only mean something to the xacro
tool. A URDF reader sees them as unknown text: properties stay unexpanded and numbers are
unreadable. Expand the file with `bras-kit xacro FILE -o FILE.urdf` (or ROS's `xacro`), or give
it the `.xacro` extension so that `bras-kit validate` expands it before checking.""",
)
describe(
    "BK120",
    title="a mimic joint follows a joint that does not exist",
    message="joint '{joint}' mimics '{leader}', which is not a joint of this robot",
    hint={
        "close": "did you mean '{close}'?",
        "": "name one of the joints: {joints}",
    },
    explanation="""\
`<mimic joint="...">` makes a joint copy another joint's value (times a multiplier, plus an
offset), as gripper fingers do. It must name another joint of the same robot.""",
)
describe(
    "BK121",
    title="mimic joints follow each other in a loop",
    message="mimic joints follow each other in a loop: {chain}",
    hint="one joint of the chain must be driven directly: remove the <mimic> from one of them",
    explanation="""\
A mimic joint copies its leader's value. If the leader mimics (directly or through others) the
first joint, no value can ever be computed: at least one joint in a mimic chain must be driven
from `/joint_states`.""",
)
describe(
    "BK122",
    title="a required attribute or element is missing",
    message={
        "element": "<{tag}> has no <{attribute}>",
        "": "<{tag}> has no '{attribute}' attribute",
    },
    hint="write it, e.g. {example}",
    explanation="""\
Some attributes and elements are required by URDF: link and joint names, the joint type, the
parent and child of a joint, a box's size, a cylinder's radius and length, a mass's value, the
six inertia values. Without them ROS's parser fails or uses a meaningless default.""",
)
describe(
    "BK123",
    title="a value is not a number",
    message={
        "comma": '<{tag}> {attribute}="{value}" writes {comma} with a decimal comma: URDF numbers take a point',
        "commas": '<{tag}> {attribute}="{value}" separates its numbers with commas: URDF separates them with spaces',
        "one": '<{tag}> {attribute}="{value}" is not a number',
        "": Plural(
            "<{tag}> {attribute}=\"{value}\" is not {count} number",
            "<{tag}> {attribute}=\"{value}\" is not {count} numbers",
            "count"),
    },
    hint={
        "comma": 'write {attribute}="{fixed}"',
        "commas": 'write {attribute}="{fixed}"',
        "one": "write one number with a decimal point, e.g. 0.6 (not 0,6 and no unit)",
        "": Plural(
            "write {count} number, e.g. {example}",
            "write {count} numbers separated by spaces, e.g. {example}",
            "count"),
    },
    explanation="""\
URDF numbers are written with a decimal point and no unit (metres, radians, kilograms), and
vectors as numbers separated by spaces: `xyz="0 0 0.6"`. A comma as decimal separator
(`0,6`), a unit (`0.6m`), a missing or extra component, or a leftover xacro expression all make
the value unreadable.""",
)

# ------------------------------------------------------------------ BK2xx joints

describe(
    "BK200",
    title="a revolute or prismatic joint has no <limit>",
    message={
        "prismatic": "prismatic joint '{joint}' has no <limit>",
        "": "revolute joint '{joint}' has no <limit>",
    },
    hint={
        "prismatic": 'add <limit lower="0" upper="0.2" effort="100" velocity="0.5"/> (metres, N, m/s)',
        "": 'add <limit lower="-1.57" upper="1.57" effort="10" velocity="1.0"/> (radians, N.m, rad/s), or make it type="continuous" if it turns freely',
    },
    explanation="""\
Revolute and prismatic joints have end stops, so URDF requires a `<limit>` with `lower`, `upper`
(radians or metres), `effort` and `velocity`. ROS's parser rejects the joint without it.
A joint that turns without stops (a wheel) is `continuous` and needs no limits.""",
)
describe(
    "BK201",
    title="<limit> without effort or velocity",
    message="joint '{joint}': <limit> is missing {missing}",
    hint="add {attributes} (maximum force or torque, and speed; any positive value works for RViz)",
    explanation="""\
A `<limit>` must give `effort` (maximum force or torque) and `velocity` (maximum speed): ROS's
parser fails with "joint limit: no effort" otherwise, even though RViz never uses them. Only
`lower` and `upper` have defaults (0).""",
)
describe(
    "BK202",
    title="lower limit above upper limit",
    message="joint '{joint}': lower limit {lower} is above upper limit {upper} {unit}",
    hint='swap them: lower="{upper}" upper="{lower}"',
    explanation="""\
The joint may move only between `lower` and `upper`; with `lower` above `upper` there is no
allowed position at all. joint_state_publisher_gui shows an unusable slider and controllers
refuse to move the joint. The two values were probably swapped, or a sign was lost.""",
)
describe(
    "BK203",
    title="the joint cannot move (lower == upper)",
    message={
        "unwritten": "joint '{joint}': <limit> gives neither lower nor upper, so both are 0 and the joint cannot move",
        "": "joint '{joint}': lower and upper are both {value} {unit}, so the joint cannot move",
    },
    hint={
        "unwritten": 'add the range, e.g. lower="-1.57" upper="1.57"',
        "": 'give a range (lower < upper), or make the joint type="fixed" if it must not move',
    },
    explanation="""\
When `lower` equals `upper`, the joint's only allowed position is that value: its slider does
not move. `lower` and `upper` default to 0 when not written, which is the usual way this
happens. If the joint really must not move, a `fixed` joint says so.""",
)
describe(
    "BK204",
    title="the joint axis is zero",
    message='joint \'{joint}\': <axis xyz="0 0 0"> has no direction',
    hint='give the direction it turns or slides about, e.g. <axis xyz="0 1 0"/>',
    explanation="""\
The axis is the direction a revolute joint turns about or a prismatic joint slides along. A
zero vector has no direction: it cannot be normalised, and the joint's motion is undefined
(KDL and simulators produce NaN positions).""",
)
describe(
    "BK205",
    title="the joint axis is not a unit vector",
    message="joint '{joint}': axis {axis} has length {norm}; it will be normalised to {unit}",
    hint='write the unit vector: <axis xyz="{unit}"/>',
    explanation="""\
URDF readers divide the axis by its length, so `0 2 0` behaves like `0 1 0`. The file still
works, but a reader of the file may believe the length matters (a gear ratio, a speed). Writing
the unit vector avoids the confusion.""",
)
describe(
    "BK206",
    title="the joint axis cannot be read",
    message={
        "missing": "joint '{joint}': <axis> has no xyz attribute",
        "comma": 'joint \'{joint}\': <axis xyz="{value}"> writes {comma} with a decimal comma: URDF numbers take a point',
        "commas": 'joint \'{joint}\': <axis xyz="{value}"> separates its numbers with commas: URDF separates them with spaces',
        "": 'joint \'{joint}\': <axis xyz="{value}"> is not three numbers',
    },
    hint={
        "comma": 'write <axis xyz="{fixed}"/>',
        "commas": 'write <axis xyz="{fixed}"/>',
        "": 'write three numbers, e.g. <axis xyz="0 1 0"/> (the tutorial\'s joints turn about y)',
    },
    explanation="""\
`<axis xyz="x y z">` needs exactly three numbers separated by spaces. ROS's parser refuses a
file whose axis it cannot read, and bras-kit's commands refuse to move such a joint rather than
pick a direction for it (the default x is probably not the one intended).""",
)
describe(
    "BK207",
    title="a number is infinite or not a number",
    message='<{tag}> {attribute}="{value}" is not a finite number',
    hint="write a finite number: inf and nan place links nowhere",
    explanation="""\
`inf`, `-inf` and `nan` are read as numbers by some parsers but make every transform that uses
them meaningless: the link and everything below it disappears or flies away. Joints without
end stops are written `continuous`, not with infinite limits.""",
)
describe(
    "BK208",
    title="a continuous joint has lower/upper limits",
    message="joint '{joint}' is continuous, so URDF readers ignore {attributes} in its <limit>",
    hint='make it type="revolute" if it must stop at these values, or remove lower/upper',
    explanation="""\
A `continuous` joint turns without end stops; URDF readers ignore `lower` and `upper` on it.
If the limits are meant, the joint is `revolute`.""",
)
describe(
    "BK209",
    title="effort or velocity limit is zero or negative",
    message={
        "effort": "joint '{joint}': effort limit {value} is not positive",
        "velocity": "joint '{joint}': velocity limit {value} is not positive",
    },
    hint={
        "effort": 'give the maximum force or torque the joint can apply, e.g. effort="10"',
        "velocity": 'give the maximum speed, e.g. velocity="1.0"',
    },
    explanation="""\
`effort` and `velocity` are maxima: a zero or negative maximum means the joint can never move
once a controller or simulator enforces limits. RViz ignores them, so the mistake goes unseen
until simulation.""",
)
describe(
    "BK210",
    title="prismatic travel is implausibly long",
    message="prismatic joint '{joint}' travels {travel} m ({lower} to {upper}); limits are in metres",
    hint='if you wrote millimetres, use lower="{lower_m}" upper="{upper_m}"',
    explanation="""\
URDF lengths are metres. A prismatic joint travelling more than 10 m is rare in an arm; the
limits were probably written in millimetres or centimetres.""",
)
describe(
    "BK211",
    title="revolute limits look like degrees",
    message="joint '{joint}': limits {lower}..{upper} exceed a full turn; URDF angles are radians",
    hint='in radians: lower="{lower_rad}" upper="{upper_rad}"',
    explanation="""\
URDF angles are radians: a quarter turn is 1.5708, not 90. Real joints may turn more than
once (an ANYmal leg ±3π, the last axis of an ABB IRB 140 ±400°, written 6.98 rad), so bras-kit
says "degrees" only for limits beyond two full turns (12.57), or beyond one turn (6.283) when
both are whole numbers (±90, ±180): radians that large are never round.""",
)
describe(
    "BK212",
    title="a fixed joint has an axis or limits",
    message={
        "axis": "joint '{joint}' is fixed, so its <axis> is ignored",
        "limit": "joint '{joint}' is fixed, so its <limit> is ignored",
        "both": "joint '{joint}' is fixed, so its <axis> and <limit> are ignored",
    },
    hint='if the joint should move, give it a moving type (type="revolute"); otherwise remove these elements',
    explanation="""\
A `fixed` joint never moves: its axis and limits are ignored. Finding them usually means the
type was meant to be `revolute` (the joint has no slider in joint_state_publisher_gui), or the
joint was copied from a moving one.""",
)
describe(
    "BK213",
    title="a moving joint has no <axis>",
    message={
        "prismatic": "joint '{joint}' has no <axis>: it slides along x (1 0 0), the URDF default",
        "": "joint '{joint}' has no <axis>: it turns about x (1 0 0), the URDF default",
    },
    hint='write the axis you mean, e.g. <axis xyz="0 1 0"/>',
    explanation="""\
Without `<axis>`, URDF uses `1 0 0`. That is valid, but a forgotten axis is a common reason
for an arm bending sideways in RViz; writing the axis makes the intent visible.""",
)
describe(
    "BK230",
    title="a <safety_controller> cannot be read",
    message={
        "missing": "joint '{joint}': <safety_controller> has no {attribute} attribute",
        "": 'joint \'{joint}\': <safety_controller {attribute}="{value}"> is not a number',
    },
    hint='write numbers, e.g. <safety_controller soft_lower_limit="-1.5" soft_upper_limit="1.5" k_position="100" k_velocity="10"/>, or remove the element',
    explanation="""\
`<safety_controller>` tells a real drive where to start braking before the hard limits
(`soft_lower_limit`, `soft_upper_limit`) and how hard (`k_position`, `k_velocity`, which is
required). urdfdom, and so every ROS tool, refuses the whole file when one of these is not a
number: a value such as `None`, left by a script that wrote a Python value, stops RViz from
showing the robot at all.""",
)

# ------------------------------------------------------------------ BK3xx the tutorial's pitfalls

describe(
    "BK301",
    title="a joint is not at the end of its parent segment",
    message={
        "short": "joint '{joint}' is at {coord}, but the {tag} of link '{link}' runs {span}: the child hangs {distance} m short of the segment's end",
        "beyond": "joint '{joint}' is at {coord}, {distance} m past the end of link '{link}' (its {tag} runs {span}): the child floats in the air",
        "beside": "joint '{joint}' is at xyz {xyz}, beside link '{link}' (its {tag} runs {span}): the child hangs {distance} m away from the segment's end",
        "detached": "joint '{joint}' is at xyz {xyz}, {distance} m away from the {tag} of link '{link}': segment '{child}' starts in the air, not on its parent",
    },
    hint={
        "detached": "put the joint on the {tag} of '{link}': {origin}",
        "": "put the joint at the end of '{link}': {origin}",
    },
    explanation="""\
A joint's `<origin>` places the child link in the parent link's frame. For an arm, each joint
sits at the end of the previous segment: the tutorial's elbow `coude` is at z = 0.6 because the
upper arm `bras` is 0.6 m long. If the origin does not match the parent's length, the next
segment starts inside the parent or floats away from it ("segments mal positionnés").

This is the tutorial's rule of thumb, so it is a warning, and bras-kit applies it only where
the parent looks like the tutorial's segments: a revolute or continuous joint whose parent link
has one box or cylinder visual clearly longer along one axis, with the joint on that axis and
within a quarter of the segment's length of its ends. When the parent is drawn exactly the
tutorial's way (its shape starts at its own joint and runs along one axis) and the child's
shape does not touch it, a joint at any distance past the end, or beside the segment, is
reported too, and so is a segment hung in the air away from any parent's shape (the arm
floating above the base). It then says where the segment ends and which origin fits (within 2 mm or 5 % of
the length). Prismatic joints (a carriage anywhere on its rail), joints beside other shapes
(motors on a chassis, a wheel under a cart) and fixed joints (sensor mounts, tool frames) are
not checked.""",
)
describe(
    "BK302",
    title="a segment's visual does not start at its joint",
    message={
        "gap": "the {tag} of link '{link}' starts {distance} m after joint '{joint}' (it runs {span}): a gap shows between the segments",
        "overlap": "the {tag} of link '{link}' reaches {distance} m behind joint '{joint}' (it runs {span}): it overlaps the previous segment",
        "centred": "the {tag} of link '{link}' is centred on joint '{joint}' (it runs {span}): half of it sticks out behind the joint",
    },
    hint="start the visual at the joint: {origin} in the <visual> of '{link}'",
    explanation="""\
A box or cylinder is centred on its `<origin>`. For a segment to start at its joint and run
along its length, its visual origin must be half its length: the tutorial's 0.6 m upper arm has
its visual at z = 0.3. With no origin (z = 0) the shape is centred on the joint and half of it
pokes backwards; with a wrong value a gap or an overlap appears at the joint.""",
)
describe(
    "BK303",
    title="a pose is outside the joint limits",
    message={
        "upper": "joint '{joint}' = {value} {unit} is {excess} {unit} above its upper limit {bound}",
        "degrees-upper": "joint '{joint}' = {value} {unit} is {excess} {unit} above its upper limit {bound}",
        "lower": "joint '{joint}' = {value} {unit} is {excess} {unit} below its lower limit {bound}",
        "degrees-lower": "joint '{joint}' = {value} {unit} is {excess} {unit} below its lower limit {bound}",
    },
    hint={
        "": "stay within {lower}..{upper} {unit}, or widen the <limit> if the mechanism allows it",
        "degrees-upper": "{value} looks like degrees: write {value}deg ({degrees} rad); otherwise stay within {lower}..{upper} {unit}",
        "degrees-lower": "{value} looks like degrees: write {value}deg ({degrees} rad); otherwise stay within {lower}..{upper} {unit}",
    },
    explanation="""\
The pose given with `--pose` puts a joint past one of its end stops. robot_state_publisher
draws the pose anyway, but a real arm or a controller would stop at the limit
("les articulations dépassent"). Keep values between `lower` and `upper`, or change the
limits if the mechanism really allows more.""",
)
describe(
    "BK304",
    title="a motion leaves the joint limits",
    message={
        "upper": "joint '{joint}' goes past its upper limit {bound} {unit} at t={time} s; worst {worst} {unit} over ({worst_value}) at t={worst_time} s",
        "lower": "joint '{joint}' goes past its lower limit {bound} {unit} at t={time} s; worst {worst} {unit} under ({worst_value}) at t={worst_time} s",
    },
    hint="keep the command within {lower}..{upper} {unit} (smaller amplitude or an offset), or widen the <limit> if the mechanism allows it",
    explanation="""\
The motion given with `--motion` (sampled at 20 Hz, like the tutorial's animation node) drives a
joint outside its limits. RViz shows it happily, a real arm would hit its stop. The finding gives
the first moment the limit is passed and the worst excess.""",
)
describe(
    "BK305",
    title="a motion is faster than the velocity limit",
    message="joint '{joint}' moves faster than its velocity limit {limit} {unit} from t={time} s; peak {speed} {unit} at t={worst_time} s",
    hint="slow the motion down (lower frequency or amplitude), or raise velocity in <limit>",
    explanation="""\
The joint's speed in the motion exceeds the `velocity` of its `<limit>`. A controller would
saturate and fall behind the command; RViz shows the motion anyway.""",
)
describe(
    "BK306",
    title="nothing in the robot can move",
    message={
        "fixed": Plural(
            "{joints} joint, and it is fixed: the robot has nothing to move",
            "all {joints} joints are fixed: the robot has nothing to move",
            "joints"),
        "": "the robot has no joint: nothing can move",
    },
    hint='give a joint a moving type, e.g. type="revolute" with an <axis> and a <limit>',
    explanation="""\
Only revolute, continuous and prismatic joints move. With none of them, joint_state_publisher_gui
opens without sliders and publishing on /joint_states changes nothing ("le robot ne bouge
pas").""",
)
describe(
    "BK307",
    title="nothing to show",
    message={
        "collisions": "no link has a <visual> (only <collision> shapes): RViz shows nothing by default",
        "": "no link has a <visual>: RViz has nothing to draw",
    },
    hint="give link '{first}' a <visual> with a <geometry> (a box, cylinder or sphere is enough)",
    explanation="""\
RViz's RobotModel display draws the `<visual>` of each link. Without any, the display stays
empty even though TF frames are published, one of the causes of "RViz reste vide" that the file
itself can cause (the others are the Fixed Frame and Description Topic settings).""",
)
describe(
    "BK308",
    title="a moving link at the end of the chain has nothing to show",
    message="link '{link}' moves with joint '{joint}' but has no <visual> and no child: moving '{joint}' changes nothing on screen",
    hint="give '{link}' a <visual> (a small box or cylinder is enough), or make '{joint}' fixed if it is only a frame",
    explanation="""\
RViz draws a link only through its `<visual>`. A link that hangs from a moving joint, has no
child and no visual can only be seen in the TF display: its slider in joint_state_publisher_gui
moves an invisible frame, which looks like "the robot does not move". A tool frame that really
is only a frame is better attached with a `fixed` joint.""",
)

# ------------------------------------------------------------------ BK4xx geometry

describe(
    "BK400",
    title="a visual or collision has no shape",
    message={
        "absent": "a <{tag}> of link '{link}' has no <geometry>",
        "unknown": "<geometry> holds <{tag}>, which is not a URDF shape",
        "": "<geometry> is empty",
    },
    hint="put one shape in <geometry>: <box size=...>, <cylinder radius=... length=...>, <sphere radius=...> or <mesh filename=...>",
    explanation="""\
Every `<visual>` and `<collision>` needs a `<geometry>` holding exactly one shape: `box`,
`cylinder`, `sphere` or `mesh`. ROS's parser fails on an empty geometry ("Geometry tag contains
no child element").""",
)
describe(
    "BK401",
    title="a size is zero or negative",
    message={
        "scale": "link '{link}': <mesh> scale {value} has a zero component: the mesh is flat",
        "": "link '{link}': <{tag}> {attribute} {value} is not positive",
    },
    hint={
        "scale": 'use 1 for an unchanged axis, e.g. scale="1 1 1"',
        "": "sizes are lengths in metres and must be positive",
    },
    explanation="""\
Box sizes, cylinder radii and lengths and sphere radii are lengths in metres; zero or negative
values draw nothing (or an inside-out shape) and break inertia computations.""",
)
describe(
    "BK402",
    title="a mesh file is missing",
    message="link '{link}': mesh '{filename}' not found (looked for {path})",
    hint="check the path; relative paths start from the URDF file's folder",
    explanation="""\
The mesh file named by `<mesh filename=...>` does not exist where a ROS tool would look. RViz
then shows nothing for this link. `package://pkg/...` is resolved through `--package-path` and
`BRAS_KIT_PACKAGE_PATH`; plain paths start from the checked file's folder.""",
)
describe(
    "BK403",
    title="a mesh's package cannot be found",
    message="link '{link}': package '{package}' of mesh '{filename}' not found, so the file was not checked",
    hint="pass --package-path DIR (a folder holding {package}/) or set BRAS_KIT_PACKAGE_PATH",
    explanation="""\
`package://name/path` points into a ROS package. Without ROS, bras-kit finds packages in the
folders given by `--package-path` or `BRAS_KIT_PACKAGE_PATH` (and in ROS's variables when they
are set). When the package is not found, the mesh cannot be checked; this is a warning because
the package may well exist on the machine that runs ROS.""",
)
describe(
    "BK404",
    title="a mesh is a web address",
    message="link '{link}': mesh '{url}' is a URL; bras-kit does not download it",
    hint="ship the mesh inside the package and use package://PACKAGE/meshes/... instead",
    explanation="""\
Meshes given as http(s) URLs are fetched at run time by some tools and not at all by others.
bras-kit never downloads anything while checking, so the mesh is not checked. A mesh inside the
description package works offline and everywhere.""",
)
describe(
    "BK405",
    title="a colour component is outside 0..1",
    message="material '{material}': rgba {rgba} has components outside 0..1",
    hint={
        "255": 'colours are fractions of 1, not bytes: rgba="{fixed}"',
        "": 'each of r g b a goes from 0 to 1, e.g. rgba="{fixed}"',
    },
    explanation="""\
URDF colours are four numbers between 0 and 1 (red, green, blue, opacity). Values written as
bytes (0..255) are clipped to 1, so the colour turns white or washes out.""",
)
describe(
    "BK406",
    title="a material is used by name but never given a colour",
    message="link '{link}' uses material '{material}', which has no colour anywhere in the file",
    hint='define it: <material name="{material}"><color rgba="0.5 0.5 0.5 1"/></material>',
    explanation="""\
`<material name="x"/>` with no `<color>` refers to a material defined elsewhere (at the top
level or in an earlier visual). When no definition with a colour exists, ROS's parser warns and
the link is drawn in the default colour.""",
)

# ------------------------------------------------------------------ BK5xx inertia

describe(
    "BK500",
    title="mass is zero or negative",
    message="link '{link}': mass {mass} is not positive",
    hint='give the mass in kilograms, e.g. <mass value="1.0"/>, or remove the <inertial> of a frame-only link',
    explanation="""\
A physics simulator divides by the mass; zero or negative masses make the simulation explode or
refuse the model. Links that are only frames (no body) should have no `<inertial>` at all.""",
)
describe(
    "BK501",
    title="inertia is not positive definite",
    message={
        "zero": "link '{link}': the inertia is all zeros",
        "": "link '{link}': the inertia is not positive definite (principal moments {moments})",
    },
    hint="compute it from the shape and mass (bras-kit validate gives the solid values when the link has one box, cylinder or sphere)",
    explanation="""\
A body's inertia matrix must be positive definite: every principal moment strictly positive.
Zero or negative moments make a simulator's dynamics meaningless (a link that spins with no
effort). Copying `ixx="0" iyy="0" izz="0"` is the usual cause.""",
)
describe(
    "BK502",
    title="principal moments violate the triangle inequality",
    message="link '{link}': principal moments {a}, {b}, {c}: the two smallest add up to less than the largest",
    hint="no real body has these moments; recompute the inertia from the shape and mass",
    explanation="""\
For any real body the principal moments of inertia satisfy A + B >= C. A tensor breaking this
rule cannot come from any mass distribution. RViz and robot_state_publisher do not use inertia,
so this is a warning, but physics engines may refuse the model (MuJoCo does unless told to
balance inertias) or simulate it wrongly. It usually means one value was mistyped, rounded or
taken from another link; many published robots carry such values.""",
)
describe(
    "BK507",
    title="a moving body's moments of inertia are impossible",
    message="link '{link}': principal moments {a}, {b}, {c}: the largest is {ratio:.2f} times the sum of the two others, which no body can have; MuJoCo refuses to load it",
    hint="recompute the inertia from the shape and mass: for a box of mass m and sides x, y, z, ixx = m (y² + z²) / 12, iyy = m (x² + z²) / 12, izz = m (x² + y²) / 12 (bras-kit urdf --inertials writes each link's formula above its <inertial>)",
    explanation="""\
For any real body the principal moments satisfy A + B >= C. A small breach is rounding (BK502,
a warning); here the largest moment is more than 1.5 times the sum of the two others, on a
link that moves. A simulator integrates that body's rotation with these numbers: MuJoCo stops
with "mass and inertia of moving bodies must satisfy A + B >= C", other engines spin it
wildly. The usual cause is a value typed in the wrong place (`izz` for `iyy`) or copied from
another link.""",
)
describe(
    "BK508",
    title="a massless appendage fused into a valid body has a negative moment",
    message="link '{link}': principal moments {moments} include a negative one, but the link is massless and fused by fixed joints into '{body}', whose inertia is valid",
    hint="write a zero inertia (or a small positive one) for this frame link",
    explanation="""\
A negative moment of inertia is impossible (BK501 says so as an error on a body that moves).
Here it belongs to a massless link fixed to a body that has a valid inertia, such as a sensor
or antenna frame: ROS tools and physics engines merge fixed links into one body, adding the
tensors, and a tiny defect of a massless part does not change what is simulated. Still worth a
clean zero.""",
)
describe(
    "BK503",
    title="inertia far from the link's shape",
    message={
        "more": "link '{link}': {key} = {given} is {factor} times what a {mass} kg {solid} gives ({expected})",
        "less": "link '{link}': {key} = {given} is {factor} times smaller than what a {mass} kg {solid} gives ({expected})",
    },
    hint="for a uniform solid: {inertia}",
    explanation="""\
The inertia is compared with that of a uniform solid of the link's own shape and mass (box:
m(b²+c²)/12 about each axis, cylinder: m(3r²+h²)/12 across and mr²/2 along, sphere: 2mr²/5).
Off by more than a factor 2 usually means swapped axes (a segment along z needs a small izz), a
unit mistake, or values copied from another link. Skipped for links with several shapes or a
mesh.""",
)
describe(
    "BK504",
    title="centre of mass far from the middle of the link's shape",
    message={
        "end": "link '{link}': the centre of mass at xyz {at} is near an end of its shape ({span}), not at its middle {centre}",
        "outside": "link '{link}': the centre of mass at xyz {at} lies outside its shape ({span})",
    },
    hint="for a uniform segment, put the <inertial> origin at the middle of the shape: {origin}",
    explanation="""\
The `<origin>` of `<inertial>` is the centre of mass. Leaving it out puts the mass at the link's
frame, that is at the joint: in simulation the segment then behaves as if all its weight sat at
its base. For a uniform segment the centre of mass is the middle of its shape (z = 0.3 for the
tutorial's upper arm). bras-kit warns when it lies outside the shape, or, for an elongated
shape, more than a quarter of its length away from the middle.""",
)
describe(
    "BK505",
    title="a moving link has no <inertial>",
    message={
        "one": "link '{link}' moves but has no <inertial>: fine for RViz, needed for physics simulation",
        "": Plural(
            "{count} moving link has no <inertial> ({links}): fine for RViz, needed for physics simulation",
            "{count} moving links have no <inertial> ({links}): fine for RViz, needed for physics simulation",
            "count"),
    },
    hint="add <inertial> with <mass> and <inertia> (try bras-kit urdf --inertials for the tutorial arm)",
    explanation="""\
RViz only draws; it never uses mass or inertia. A physics simulator such as Gazebo ignores, or
refuses, links without `<inertial>`: this is the tutorial's "aller plus loin" exercise. A note,
not a problem, while you only visualise the arm; it is given once per robot, naming the links.""",
)
describe(
    "BK506",
    title="the root link has an inertia",
    message="root link '{link}' has an <inertial>: robot_state_publisher (KDL) ignores it and prints a warning",
    hint="harmless in RViz; for simulation add a root link without inertia (e.g. 'world') fixed to '{link}'",
    explanation="""\
KDL, which robot_state_publisher uses, does not support an inertia on the root link and warns
about it at start-up. RViz is unaffected. Simulators that need it usually add a massless root
link (`world` or `base_footprint`) with a fixed joint to the real base.""",
)
