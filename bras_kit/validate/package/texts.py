"""The English words of the package rules (BK6xx). French: ``validate.po`` (msgctxt = code)."""

from __future__ import annotations

from ...findings.registry import Plural, describe

# ------------------------------------------------------------------ BK6xx the ROS 2 package

describe(
    "BK600",
    title="a file of the package cannot be read",
    message={
        "missing": "{file} is missing: this is not a complete ament_python package",
        "": "{file} cannot be read: {detail}",
    },
    hint={
        "missing": "run 'bras-kit new' to see a complete package, or add the missing file",
        "": "fix this line; the package rules that need this file were skipped",
    },
    explanation="""\
The package checks read `package.xml` (as XML), `setup.py`, the launch files and the Python
nodes (as Python source, without running them) and the `.rviz` files (as YAML). A file that is
missing or cannot be parsed is reported here, and the checks that need it say nothing: fix this
first. colcon and `ros2 launch` would fail on the same file.""",
)
describe(
    "BK601",
    title="a folder the launch needs is not installed by setup.py",
    message={
        "all": "setup.py does not install {folder}/ ({files}): 'ros2 launch' will say file not found",
        "some": "setup.py does not install {files} from {folder}/: 'ros2 launch' will not find them",
        "elsewhere": "setup.py installs {files} into {destination}, not {target}: 'ros2 launch' will say file not "
                     "found",
        "slash": "setup.py installs {files} into {destination}, not {target}: 'ros2 launch' will say file not found",
        "": "setup.py does not install {files} from {folder}/",
    },
    hint={
        "slash": "write this entry's destination as {entry}: a '/' is missing between the package name and "
                 "'{folder}'; then run colcon build again",
        "elsewhere": "write this entry's destination as {entry}, then run colcon build again",
        "": "add {entry} to data_files, then run colcon build again",
    },
    explanation="""\
colcon copies into `install/PKG/share/PKG/` only what `data_files` in `setup.py` lists. The
launch file then looks for the URDF (and itself is found) there, not in the source folder. A
package that forgets `urdf/` or `launch/` builds without a word and fails at `ros2 launch`
with "file not found": the tutorial's third pitfall. Each folder needs its own entry
`(os.path.join('share', package_name, 'urdf'), glob('urdf/*.urdf'))`, and a new build.""",
)
describe(
    "BK602",
    title="the launch file opens a file that is not installed",
    message={
        "exists": "opens share/{package}/{path}: {path} exists but setup.py does not install it",
        "other": "opens share/{package}/{path}, but setup.py installs only {installed} in {folder}/",
        "": "opens share/{package}/{path}, which no file of the package installs",
    },
    hint={
        "exists": "add {path} to data_files in setup.py, then run colcon build again",
        "other": "use one of the installed names ({installed}), or install {path}",
        "": "fix the file name, or add the file to the package and to data_files",
    },
    explanation="""\
The launch file builds paths in the installed share folder (`get_package_share_directory`,
`FindPackageShare`) and opens them, or passes them to a node. Such a path must name a file that
`setup.py` installs there, with the same folder and name: otherwise launching fails with "file
not found". A renamed URDF or a typo in the launch file is the usual cause. Paths are compared
as the system resolves them: `os.path.join(get_package_share_directory(PKG))`, 'urdf/', './',
a doubled slash or a '..' that stays inside the share folder name the same file. RViz's `-d` is
not judged here: RViz opens its default configuration when it cannot load one (BK613).""",
)
describe(
    "BK603",
    title="the package is not registered in the ament index",
    message={
        "file": "{marker} is missing: ros2 cannot find the package {package} once installed",
        "entry": "data_files does not install {marker} in share/ament_index/resource_index/packages: ros2 cannot find the package {package}",
        "": "the package {package} is not registered in the ament index ({marker})",
    },
    hint={
        "file": "create the empty file {marker}",
        "": "add ('share/ament_index/resource_index/packages', ['{marker}']) to data_files",
    },
    explanation="""\
`ros2 launch`, `ros2 run` and `get_package_share_directory` find installed packages through the
ament index: an empty file named after the package, installed in
`share/ament_index/resource_index/packages`. `ros2 pkg create` makes `resource/PKG` and the
`data_files` entry; deleting either gives "package not found" although the build succeeded.""",
)
describe(
    "BK604",
    title="the names in package.xml and setup.py differ",
    message="package.xml names the package '{xml_name}' but setup.py (line {setup_line}) names it '{setup_name}'",
    hint="use one name everywhere: <name> in package.xml, package_name in setup.py, resource/NAME",
    explanation="""\
colcon knows the package by the `<name>` of `package.xml`; setuptools installs it under the
name given in `setup.py`, and the launch file looks for its share folder by name. When they
differ, files land in one folder and are looked for in another: "package not found" or
"file not found" at launch. Renaming a package means changing all of them.""",
)
describe(
    "BK605",
    title="a package the launch file starts is not declared in package.xml",
    message="the launch file {launch} (line {launch_line}) starts a node of '{dependency}', which package.xml does not list as <exec_depend>",
    hint="add <exec_depend>{dependency}</exec_depend> to package.xml",
    explanation="""\
`rosdep install` installs what `package.xml` declares. A node started by the launch file
but not declared works on the machine where it happens to be installed, and fails elsewhere
with "package not found". Every package whose nodes the launch file starts
(robot_state_publisher, joint_state_publisher_gui, rviz2...) belongs in an `<exec_depend>`.
This is advice (info): the tutorial's own package declares none of them and runs on a machine
where ROS 2 desktop is installed.""",
)
describe(
    "BK608",
    title="the package does not hold the next step's file yet",
    message={
        "urdf": "no robot description yet: urdf/ holds no .urdf or .xacro file",
        "launch": "no launch file yet: launch/ holds no .launch.py file",
        "node": "setup.py runs '{executable}' from {node_file}, not written yet: 'ros2 run {package} {executable}' "
                "fails until it is",
        "": "the package does not hold the next step's file yet",
    },
    hint={
        "urdf": "next step: describe the robot in urdf/bras.urdf (the tutorial's step 3)",
        "launch": "next step: write launch/affichage.launch.py (the tutorial's step 4)",
        "node": "next step: write {node_file} with its main() (the tutorial's step 7)",
        "": "write the next step's file",
    },
    explanation="""\
A package made as the tutorial makes it (`ros2 pkg create`, or `bras-kit new --empty`) gets its
files one step at a time: the robot description (step 3), the launch file (step 4), the
`data_files` of `setup.py` (step 5), the node and its `console_scripts` entry (step 7). What is
not written yet is the next step, not a mistake: this finding names it (info), and the rules
that check a file start once it exists. A `console_scripts` entry whose module file is missing
is reported here rather than as BK622, since `colcon build` succeeds and only
`ros2 run` fails, until the file is written. A file of that name elsewhere in the package (beside
`setup.py`, in another folder, in another case) is written, in the wrong place: BK622 says so,
as an error.""",
)
describe(
    "BK606",
    title="invalid maintainer email in package.xml",
    message={
        "none": "package.xml has no <maintainer>",
        "missing": "maintainer '{maintainer}' has no email attribute",
        "": "maintainer '{maintainer}' has an invalid email '{email}': colcon will not see a ROS package",
    },
    hint={
        "none": 'add <maintainer email="you@example.com">Your Name</maintainer>',
        "": 'write a real address: <maintainer email="you@example.com">',
    },
    explanation="""\
colcon reads `package.xml` with catkin_pkg, which refuses a maintainer without a valid email
address (name@domain.tld). colcon then ignores the manifest, builds the folder as a plain Python
package and never installs the ament index marker: `ros2 launch` cannot find the package
although the build looked fine. Placeholders such as `TODO` are the usual cause.""",
)
describe(
    "BK610",
    title="the RViz Fixed Frame is not a link of the robot",
    message={
        "missing": "the RViz configuration sets no Fixed Frame: RViz keeps its own, '{frame}', which is no link of this robot",
        "argument": "rviz2 is started with -f {frame}, which is not a link of the robot ({links}): RViz shows nothing",
        "": "Fixed Frame '{frame}' is not a link of the robot ({links}): RViz shows nothing",
    },
    hint={
        "argument": "give -f the robot's root link, '{root}' (-f wins over the configuration's Fixed Frame)",
        "": "set Fixed Frame to '{root}' (Global Options > Fixed Frame)",
    },
    explanation="""\
RViz draws everything relative to its Fixed Frame. When no TF frame has that name (the
default `map`, or a link that was renamed), RViz shows "Frame does not exist" and an empty
view: the tutorial's first pitfall. Use the robot's root link, `base` in the tutorial.""",
)
describe(
    "BK611",
    title="the RViz configuration does not show the robot model",
    message={
        "missing": "the RViz configuration has no RobotModel display: the arm is not drawn",
        "disabled": "the RobotModel display is disabled: the arm is not drawn",
        "topic": "RobotModel reads its description from '{topic}', not /robot_description",
        "namespace": "RobotModel reads its description from '{topic}', but robot_state_publisher publishes it on "
                     "{published} ({launch}): the arm is not drawn",
        "": "the RobotModel display is not set up",
    },
    hint={
        "missing": "add a RobotModel display with Description Topic /robot_description, and save the configuration",
        "disabled": "tick the RobotModel display (Enabled: true) and save the configuration",
        "namespace": "set Description Topic to {published}, or start robot_state_publisher outside the namespace",
        "": "set Description Topic to /robot_description",
    },
    explanation="""\
robot_state_publisher publishes the URDF on the topic `robot_description`, a relative name: rcl
resolves it in the node's namespace and through its remappings, so it is `/robot_description`
at the root and `/bras/robot_description` under `PushRosNamespace('bras')` or `namespace='bras'`.
RViz's RobotModel display draws the links only when it reads that very topic; with another topic,
or no RobotModel at all, RViz stays empty although everything runs: the tutorial's first pitfall.
With the launch file evaluated (`--launch`, `bras-kit launch`), both names are resolved as rcl
resolves them (namespaces, remappings, `~/`).""",
)
describe(
    "BK612",
    title="the RViz configuration has no TF display",
    message="no TF display: the link frames are not shown",
    hint="add a TF display (Add > TF) to see each link's frame, and save the configuration",
    explanation="""\
The TF display draws each link's frame and names: it is how the tutorial shows what
robot_state_publisher computes. The robot model still appears without it, so this is advice,
not a defect.""",
)
describe(
    "BK613",
    title="RViz is started without a configuration",
    message={
        "unused": "rviz2 is started without -d, so {config} is not used: RViz opens empty",
        "missing": "rviz2 is given -d {config}, which the package does not have: RViz opens its default "
                   "configuration, empty",
        "not_installed": "rviz2 is given -d {config}, which setup.py does not install: RViz says it cannot load it "
                         "and opens its default configuration, empty",
        "": "rviz2 is started without a configuration: RViz opens empty",
    },
    hint={
        "missing": "save RViz's configuration as {config} (File > Save Config As), install it, or correct the name",
        "not_installed": "add {config} to data_files in setup.py, then run colcon build again",
        "unused": "pass arguments=['-d', os.path.join(get_package_share_directory('{package}'), '{config}')]",
        "": "save a configuration to rviz/{package}.rviz, install it, and pass it with arguments=['-d', ...]",
    },
    explanation="""\
Started with no `-d`, RViz opens its default configuration: Fixed Frame `map`, no robot model.
The tutorial then sets Fixed Frame and adds RobotModel by hand, at every launch. Saving that
configuration in the package, installing it and passing it with `-d` shows the arm at once.
Given with `-d` a file it cannot find (not in the package, or not installed by `setup.py`), RViz
logs an error and opens its default configuration: the launch starts, which is why this is
advice (info), not an error.""",
)
describe(
    "BK615",
    title="the launch file starts no RViz",
    message="the launch file starts robot_state_publisher but no rviz2: ros2 launch opens no RViz window, so "
            "nothing shows the robot",
    hint="add Node(package='rviz2', executable='rviz2') to the launch file, or run 'ros2 run rviz2 rviz2' in "
         "another terminal",
    explanation="""\
robot_state_publisher publishes the robot and its frames; only RViz (the `rviz2` node) draws
them. A launch file without `Node(package='rviz2', executable='rviz2')` runs and shows nothing:
start RViz from the launch file, or with `ros2 run rviz2 rviz2` beside it, then set it up
(Fixed Frame, Add RobotModel, TF: the tutorial's step 6). Judged on the evaluated launch
(`bras-kit launch`, `validate --launch`), the same reading of rviz2's start the page uses; a
launch file another one includes is judged with it.""",
)
describe(
    "BK620",
    title="nothing publishes /joint_states",
    message={
        "nodes": Plural(
            "the launch file starts robot_state_publisher but nothing that publishes /joint_states ({node} does, but is not started): the joint {joints} has no angle",
            "the launch file starts robot_state_publisher but nothing that publishes /joint_states ({node} does, but is not started): the joints {joints} have no angle",
            "joints"),
        "topic": Plural(
            "robot_state_publisher listens on {listens}, but JointState is published elsewhere ({sources}): the joint {joints} has no angle",
            "robot_state_publisher listens on {listens}, but JointState is published elsewhere ({sources}): the joints {joints} have no angle",
            "joints"),
        "": Plural(
            "the launch file starts robot_state_publisher but nothing that publishes /joint_states: the joint {joints} has no angle",
            "the launch file starts robot_state_publisher but nothing that publishes /joint_states: the joints {joints} have no angle",
            "joints"),
    },
    hint={
        "topic": "put them in the same namespace (one GroupAction with PushRosNamespace), or remap: "
                 "remappings=[('joint_states', '{listens}')]",
        "": "start joint_state_publisher_gui (or your animation node) in the launch file",
    },
    explanation="""\
robot_state_publisher computes the frames of moving links from the angles it receives on
`/joint_states`. With no publisher, those links have no transform: RViz shows them at the
origin or not at all, and nothing moves. The tutorial's second pitfall; joint_state_publisher_gui
or an animation node must run.""",
)
describe(
    "BK621",
    title="a node publishes JointState names that are not the robot's joints",
    message={
        "unknown": "JointState names {names}, which are not movable joints of the robot ({joints})",
        "unknown_one": "JointState names {names}, which is not a movable joint of the robot ({joints})",
        "missing": "JointState never names {names} (it names {published}): those joints do not move",
        "missing_one": "JointState never names {names} (it names {published}): that joint does not move",
        "": "JointState names do not match the robot's movable joints",
    },
    hint={
        "unknown": "use the joint names of the URDF: {joints}",
        "unknown_one": "use the joint names of the URDF: {joints}",
        "missing": "add {names} to the names, with a position for each",
        "missing_one": "add {names} to the names, with its position",
        "": "name every movable joint of the URDF",
    },
    explanation="""\
robot_state_publisher matches JointState entries to the URDF by name. A name the robot does
not have is ignored; a movable joint that is never named has no transform, so its child link
and everything after it do not move (or disappear from RViz). The usual cause: a joint added
to the URDF, such as the tutorial's `poignet`, but not to the node's `msg.name`.""",
)
describe(
    "BK622",
    title="a node has no console_scripts entry point",
    message={
        "launch": "the launch file starts '{executable}' of {package}, but setup.py declares no console_scripts entry of that name",
        "node": "{node_file} publishes JointState and has main(), but no console_scripts entry runs it",
        "module": "console_scripts entry '{executable}' points to {module}, which does not exist",
        "function": "console_scripts entry '{executable}' points to {module}:{function}, which is not defined",
        "elsewhere": "console_scripts entry '{executable}' runs {node_file}, found elsewhere ({found}), where colcon "
                     "does not install it: 'ros2 run {package} {executable}' fails with ModuleNotFoundError",
        "": "a node has no console_scripts entry point",
    },
    hint={
        "launch": "add {entry} to entry_points['console_scripts'] in setup.py",
        "node": "add {entry} to entry_points['console_scripts'] in setup.py",
        "elsewhere": "move {moved} to {node_file}, the file the entry {module} names, then run colcon build again",
        "": "point the entry at an existing module and function (module.path:main)",
    },
    explanation="""\
`ros2 run PKG NAME` and a launch file's `Node(package=PKG, executable=NAME)` run the programs
that `setup.py` declares under `entry_points['console_scripts']` (`'NAME = PKG.module:main'`).
A node without an entry is never installed as a program: "No executable found", and the robot
does not move. An entry `PKG.module` runs the file `PKG/module.py`, in that folder and with that
case: setuptools' `packages=[package_name]` installs the `.py` files of the package folder and
nothing else, so a node saved beside `setup.py`, in `launch/`, in a subfolder, in a folder of
another name or as `Module.py` builds without a word and `ros2 run` fails with
ModuleNotFoundError. This finding then says where the file is and where it must go.""",
)
describe(
    "BK623",
    title="a node's motion leaves the joint limits",
    message={
        "upper": "joint '{joint}' follows {formula}: above its upper limit {bound} from t = {time} s, up to {value} {unit}",
        "lower": "joint '{joint}' follows {formula}: below its lower limit {bound} from t = {time} s, down to {value} {unit}",
        "": "joint '{joint}' follows {formula}, which leaves its limits",
    },
    hint="shrink the amplitude so that it stays between lower and upper, or widen the URDF's limits",
    explanation="""\
When a node writes its positions as literal formulas (`0.8 * math.sin(t)`), bras-kit follows
each one for a minute with the same limit checks as `--motion` and compares it with the
joint's `<limit>`. robot_state_publisher draws what it receives, so the arm goes past its
stops in RViz, and a real robot or a simulator would refuse it: the tutorial's fifth pitfall.
Formulas that are not literal (read from parameters, computed elsewhere) are not judged.""",
)

# ------------------------------------------------------------------ BK6xx the ROS 2 package

describe(
    "BK640",
    title="the node raised an exception when run",
    message="the node raised {kind} at t = {time} s of simulated time: {detail}",
    hint="the traceback above shows your file and line; ros2 run would stop the node there too",
    explanation="""\
`bras-kit run` ran the node's `main()` against its stand-in for rclpy (Jazzy), and the node's
own code raised. The stand-in checks what rclpy 7.1 checks: a Node made before `rclpy.init()`,
or spun after `destroy_node()`, fails like rclpy; message setters check types only with
`ROS_PYTHON_CHECK_FIELDS=1`, as on Jazzy. The traceback keeps your frames only, and the
simulated time tells at which tick. The mistakes BK652 recognises are explained there instead.""",
)
describe(
    "BK641",
    title="the node uses a part of ROS 2 that bras-kit does not simulate",
    message="the node uses {what} (at t = {time} s), which bras-kit run does not simulate",
    hint="run it with ros2 run on a ROS 2 machine, the real thing; bras-kit run covers rclpy's basics (nodes, publishers, subscriptions, timers, rates, parameters, logs) and common messages",
    explanation="""\
The stand-in follows rclpy 7.1 (Jazzy) where beginner nodes use it: `rclpy.init/spin/
spin_once/shutdown/try_shutdown`, `Node` with publishers, subscriptions, timers, rates, the
parameters API, clock and logger, executors and callback groups, threads, QoS profiles, tf2_ros,
and every message package of Jazzy's definitions. Services, actions and a few rarer calls are
not simulated: the run stops there rather than pretend. A message package is one of those
definitions, whatever a name says: a module of yours named like one (`test_from_std_msgs.py`, a
package `bras_msgs`) runs as your code; a package of Jazzy bras-kit holds no definitions of
(`control_msgs`, `turtlesim`) or one a ROS install generated is not simulated (this finding); any
other name fails as on Jazzy, with ModuleNotFoundError (BK652).""",
)
describe(
    "BK642",
    title="the node publishes in a loop that lets no time pass",
    message="the node published thousands of messages on {topics} without any time passing (stopped at t = {time} s)",
    hint="publish from a timer (create_timer) and spin, or sleep in the loop (time.sleep(0.05))",
    explanation="""\
A `while` loop that publishes and never sleeps, spins or waits sends messages as fast as the
processor allows: hundreds of thousands per second on a real machine, a flood for
robot_state_publisher and RViz, and one CPU core at 100 %. bras-kit's clock never moves in
such a loop, so the run stops it after ten thousand messages at the same instant.""",
)
describe(
    "BK643",
    title="rate.sleep() with no executor spinning: a real node would block",
    message=Plural(
        "the node called rate.sleep() {count} time with no executor spinning in another thread",
        "the node called rate.sleep() {count} times with no executor spinning in another thread",
        "count"),
    hint="use create_timer and rclpy.spin, or spin the node in a thread before the loop",
    explanation="""\
In rclpy, `Rate.sleep()` waits for a timer that an executor must be spinning, in another
thread (rclpy/timer.py). A node that calls it in its main loop without spinning elsewhere
blocks forever at its first sleep under `ros2 run`. bras-kit's simulated clock lets the loop go
on so the rest can be checked, and reports it here.""",
)
describe(
    "BK644",
    title="nothing was published on /joint_states",
    message={
        "other": Plural(
            "nothing was published on /joint_states; the JointState messages went to {topics} ({count} message): robot_state_publisher does not listen there",
            "nothing was published on /joint_states; the JointState messages went to {topics} ({count} messages): robot_state_publisher does not listen there",
            "count"),
        "type": "/joint_states carried {types}, not sensor_msgs/msg/JointState",
        "silent": "the node made a JointState publisher on {topic} but never published on it in {time} s",
        "": "nothing was published on /joint_states in {time} s (topics published: {topics})",
    },
    hint={
        "other": "create the publisher on 'joint_states' (or '/joint_states'), the topic robot_state_publisher subscribes to",
        "type": "publish sensor_msgs.msg.JointState messages on /joint_states",
        "silent": "call publish(msg) at each tick (in the timer's callback), and spin the node",
        "": "create a JointState publisher on 'joint_states' and publish from a timer",
    },
    explanation="""\
robot_state_publisher takes the joint angles from `/joint_states` and nowhere else. A node
that publishes on `joint_state` or `/arm/joint_states` is valid ROS (any such name is a legal
topic) but nobody reads it: the robot appears and does not move, the tutorial's second
pitfall. Publishing nothing at all (no timer, no spin, `publish` forgotten) looks the same.""",
)
describe(
    "BK645",
    title="JointState name and position lists of different lengths",
    message=Plural(
        "a JointState names {named} but gives {given} (t = {time} s; {count} such message)",
        "a JointState names {named} but gives {given} (t = {time} s; {count} such messages)",
        "count"),
    hint="give one position per name, in the same order",
    parts={
        "named": Plural("{names} joint", "{names} joints", "names"),
        "given": Plural("{positions} position", "{positions} positions", "positions"),
    },
    explanation="""\
robot_state_publisher pairs `name[i]` with `position[i]`. When the two lists differ in length it
drops the whole message with an error ("has 2 joint names but 3 positions"), so the arm does not
move at all, even for the joints that were right.""",
)
describe(
    "BK646",
    title="the node names joints the robot does not have",
    message={
        "": "the node's JointState names {names}, which are not movable joints of the robot ({joints})",
        "one": "the node's JointState names {names}, which is not a movable joint of the robot ({joints})",
        "split": Plural(
            "msg.name was given one string, '{value}', not a list: ROS sends {letters_as} ({count} message)",
            "msg.name was given one string, '{value}', not a list: ROS sends {letters_as} ({count} messages)",
            "count"),
    },
    hint={
        "": "use the joint names of the URDF: {joints}",
        "one": "use the joint names of the URDF: {joints}",
        "split": "give a list of names: msg.name = {names}",
    },
    parts={
        "letters_as": Plural(
            "its {letters} letter as {letters} joint name",
            "its {letters} letters as {letters} joint names",
            "letters"),
    },
    explanation="""\
robot_state_publisher matches JointState entries to the URDF by name and ignores the others. A
misspelt name (`Coude`, `elbow`, `coude_joint`) therefore leaves that joint without an angle,
though the node runs without an error. The run shows the names actually sent.""",
)
describe(
    "BK647",
    title="movable joints the node never names",
    message={
        "": "the node's JointState never names {names} (it names {published}): those joints do not move",
        "one": "the node's JointState never names {names} (it names {published}): that joint does not move",
    },
    hint={
        "": "add {names} to msg.name, with a position for each",
        "one": "add {names} to msg.name, with its position",
    },
    explanation="""\
A movable joint that never appears on `/joint_states` has no transform: robot_state_publisher
cannot place its child link, which RViz then shows at the origin or not at all. The usual cause
is a joint added to the URDF (the tutorial's `poignet`) but not to the node's message.""",
)
describe(
    "BK648",
    title="a position that is not a number",
    message="joint '{joint}' was sent the position {value} at t = {time} s",
    hint="check the computation (a division by zero, math.inf, a NaN read from a sensor)",
    explanation="""\
A JointState message accepts NaN and infinity (the generated classes only check the type), but
no transform can be computed from them: robot_state_publisher publishes garbage frames and RViz
draws nothing or warns. The run reports the first such value of each joint.""",
)
describe(
    "BK649",
    title="positions published past the joint limits",
    message={
        "upper": Plural(
            "joint '{joint}' was sent {value} {unit} at t = {time} s, above its upper limit {bound} ({count} message past it, first at t = {first} s)",
            "joint '{joint}' was sent {value} {unit} at t = {time} s, above its upper limit {bound} ({count} messages past it, first at t = {first} s)",
            "count"),
        "lower": Plural(
            "joint '{joint}' was sent {value} {unit} at t = {time} s, below its lower limit {bound} ({count} message past it, first at t = {first} s)",
            "joint '{joint}' was sent {value} {unit} at t = {time} s, below its lower limit {bound} ({count} messages past it, first at t = {first} s)",
            "count"),
        "degrees": Plural(
            "joint '{joint}' was sent {value} at t = {time} s, past its limit {bound}: it looks like degrees ({count} message, first at t = {first} s)",
            "joint '{joint}' was sent {value} at t = {time} s, past its limit {bound}: it looks like degrees ({count} messages, first at t = {first} s)",
            "count"),
    },
    hint={
        "upper": "keep the positions between the URDF's lower and upper limits (in radians)",
        "lower": "keep the positions between the URDF's lower and upper limits (in radians)",
        "degrees": "JointState positions are radians: convert with math.radians()",
    },
    explanation="""\
robot_state_publisher draws whatever it receives: past a `<limit>` the arm goes through its own
stops in RViz, and a real robot or simulator would refuse the command. The tutorial's fifth
pitfall, seen in the messages the node actually sent (degrees instead of radians are the most
common cause).""",
)
describe(
    "BK650",
    title="header.stamp left at zero",
    message=Plural(
        "{count} of {total} JointState messages has header.stamp at zero",
        "{count} of {total} JointState messages have header.stamp at zero",
        "count"),
    hint="set msg.header.stamp = self.get_clock().now().to_msg() before publishing",
    explanation="""\
robot_state_publisher stamps the frames it publishes with the JointState's time. A stamp of zero
(1 January 1970) makes the transforms look more than fifty years old: RViz and tf2 refuse to use them
("extrapolation into the past") or use them late. The tutorial's node stamps each message with
the node's clock for this reason.""",
)
describe(
    "BK651",
    title="publication rate far from the timer's",
    message="/joint_states was published at {rate} Hz, but the timer of {period} s asks for {expected} Hz",
    hint="publish once per timer callback (not in a loop inside it, not only sometimes)",
    explanation="""\
A node with one timer that publishes once per tick sends messages at the timer's rate (20 Hz
for the tutorial's 0.05 s). A very different rate means the callback publishes several times,
or only now and then, or that another loop publishes: the motion in RViz then jerks or races.""",
)
describe(
    "BK624",
    title="the node publishes JointState on another topic than /joint_states",
    message="the node publishes its JointState on '{topic}': robot_state_publisher listens on /joint_states only, so the arm never moves",
    hint="publish on 'joint_states': {fix}",
    explanation="""\
robot_state_publisher subscribes to `/joint_states` and nothing else. A publisher created on
`'joint_state'`, `'/joint_states/'` misspelled or any other name sends its messages to a topic
nobody listens to: no error anywhere, the arm simply stays still in RViz (the tutorial's
"le robot ne bouge pas"). The topic is read from the `create_publisher` call, written literally
or as a constant of the module; `'joint_states'` and `'/joint_states'` are both right.""",
)
describe(
    "BK625",
    title="the node never sends its JointState",
    message={
        "publish": "the node creates a JointState publisher but never calls publish(): nothing reaches /joint_states",
        "timer": "the node creates a JointState publisher but no timer or loop ever runs the code that publishes: nothing reaches /joint_states",
    },
    hint={
        "publish": "publish the message at the end of the callback: {fix}",
        "timer": "schedule the callback in __init__: {fix}",
    },
    explanation="""\
Creating a publisher sends nothing by itself. The tutorial's node builds a JointState in
`tick()`, sends it with `self.pub.publish(msg)`, and `self.create_timer(0.05, self.tick)` calls
`tick()` twenty times a second while `rclpy.spin()` runs. Without the timer (and without a loop
of its own) the callback never runs; without `publish()` the message is built and thrown away.
Either way robot_state_publisher receives no angle and the arm does not move.""",
)
describe(
    "BK626",
    title="the node publishes angles in degrees",
    message="the node writes its angles in degrees ({what}): JointState positions are radians, so the arm turns 57 times too far",
    hint="give radians: drop the conversion (math.radians(45) if you think in degrees; 0.8 rad is about 46 degrees)",
    explanation="""\
Every angle in ROS is in radians: URDF limits, `JointState.position`, TF. A node that converts
with `math.degrees(...)`, multiplies by `180 / math.pi`, or writes amplitudes such as `45 *
math.sin(t)` for a revolute joint sends numbers 57 times too large: the arm spins through its
stops in RViz, and a real controller would refuse them. An amplitude beyond 2 pi (a full turn)
on a revolute joint is read as degrees.""",
)
describe(
    "BK607",
    title="setup.py uses a name it never imports or defines",
    message="setup.py uses '{undefined}', which it never imports or defines: colcon build will stop with NameError: name '{undefined}' is not defined",
    hint={
        "known": "add this line at the top of setup.py: {fix}",
        "": "import or define '{undefined}' before setup(...), or write its value instead",
    },
    explanation="""\
colcon builds an ament_python package by running its `setup.py` as a Python program. The
tutorial's data_files lines call `os.path.join(...)` and `glob(...)` and use `package_name`:
they need `import os`, `from glob import glob` and `package_name = '...'` at the top of the
file. A `setup.py` made by `ros2 pkg create` defines `package_name` but imports neither `os`
nor `glob`, so pasting the tutorial's lines there alone stops the build with `NameError`.""",
)
describe(
    "BK614",
    title="robot_state_publisher is started without robot_description",
    message={
        "none": "the launch file starts robot_state_publisher without parameters: it never gets the robot_description, so RViz stays empty",
        "": "the launch file starts robot_state_publisher without a robot_description parameter: RViz stays empty",
    },
    hint="read the installed URDF and pass its text: {fix}",
    explanation="""\
robot_state_publisher learns the robot's shape from one parameter, `robot_description`, which
holds the URDF's text (not its path). The tutorial's launch file reads the installed
`urdf/bras.urdf` and passes `parameters=[{'robot_description': description}]`. Without it the
node waits for a description that never comes: no `/robot_description`, no TF frames, and
RViz's RobotModel stays empty. Parameters given as a YAML file or built by substitutions are
not judged here.""",
)
describe(
    "BK652",
    title="the node made a beginner's mistake that rclpy (Jazzy) stops on",
    message={
        "wrong_import": "'from {module} import {type}' fails: {type} is not in {module} but in {home}",
        "unknown_import": "'from {module} import {type}' fails: ROS 2 Jazzy has no message {type} in {module}",
        "misspelt_import": "'from {module} import {type}' fails: ROS 2 Jazzy has no {type}; the closest is {close}, in {home}",
        "misspelt_package": "'{module}' is no interface package of ROS 2 Jazzy (the closest is {close}): the import "
                            "fails with ModuleNotFoundError",
        "unknown_package": "'{module}' is no interface package bras-kit knows of ROS 2 Jazzy, nor a module of yours: "
                           "the import fails with ModuleNotFoundError, as with ros2 run on a machine without it",
        "shutdown_twice": "rclpy.shutdown() after Ctrl-C raised '{detail}': rclpy's Ctrl-C handler had already shut the context down",
        "with_node": "'with {cls}() as node:' fails: a Node of rclpy 7.1 (Jazzy) is not a context manager",
        "spin_forgotten": "main() returned at t = 0 s without spinning: the timer created here never fired",
        "super_init": "{cls}.__init__ never calls super().__init__('node_name'): the Node is not set up ({detail})",
        "timer_period": "create_timer({period}, ...) fires every {period} s, not {period} times a second: nothing in {duration} s",
        "now_not_msg": "header.stamp was given an rclpy Time (get_clock().now()) instead of a message: publishing aborted the process",
        "field_type": "field '{field}' holds a {held} where the message wants another type: publishing aborted the process",
        "callback_called": "create_timer was given the result of {callback}() (None) instead of the method: the first tick raised",
        "no_self": "{callback} is defined without 'self': the timer calls it on the node and it raised {detail}",
        "no_main": "the module has no function {function}(): ros2 run stops with \"module has no attribute '{function}'\"",
        "stamp_seconds": Plural(
            "header.stamp only counts whole seconds (nanosec left at 0): {distinct_stamps} for {count} message",
            "header.stamp only counts whole seconds (nanosec left at 0): {distinct_stamps} for {count} messages",
            "count"),
    },
    hint={
        "wrong_import": "import it from its package: from {home} import {type} (and add the package to package.xml's <depend>)",
        "unknown_import": "check the type's name and package (ros2 interface list on a ROS 2 machine)",
        "misspelt_import": "write from {home} import {close}",
        "misspelt_package": "write {close}",
        "unknown_package": "check the package's name (ros2 interface packages on a ROS 2 machine); a package of your "
                           "workspace is found once built and sourced (source install/setup.bash)",
        "shutdown_twice": "end main() with rclpy.try_shutdown() (or 'if rclpy.ok(): rclpy.shutdown()')",
        "with_node": "write node = {cls}() then node.destroy_node() at the end (an executor, not a Node, can be used with 'with')",
        "spin_forgotten": "call rclpy.spin(node) after creating the node: spin is what runs the timers",
        "super_init": "make super().__init__('node_name') the first line of {cls}.__init__",
        "timer_period": "give the period in seconds: create_timer(1 / {period}, ...) = {hz} s for {period} Hz",
        "now_not_msg": "write msg.header.stamp = self.get_clock().now().to_msg()",
        "field_type": "give the field a {wanted} value (0.0 rather than 0 for a float field)",
        "callback_called": "pass the method without calling it: create_timer(period, self.{short})",
        "no_self": "define it as def {short}(self):",
        "no_main": "add def {function}(): ... to the module, or make setup.py's console_scripts point at the function that starts the node",
        "stamp_seconds": "write msg.header.stamp = self.get_clock().now().to_msg(): it fills sec and nanosec",
    },
    parts={
        "distinct_stamps": Plural(
            "{distinct} distinct stamp",
            "{distinct} distinct stamps",
            "distinct"),
    },
    explanation="""\
These are the mistakes that stop a beginner's node on ROS 2 Jazzy (rclpy 7.1) with a message
that says little about the cause. bras-kit recognises each from what the run did and points at
the line to change: the `def`, the `create_timer` call, the class. On Jazzy, message setters no
longer check types (rosidl_python 0.18+): a wrong type is only found when the message is
published, by the C conversion, and the process aborts without a Python traceback. After
Ctrl-C, rclpy has already shut its context down: a second `rclpy.shutdown()` raises. An
interface package Jazzy does not have (`sensors_msgs`) stops the node at its import with
ModuleNotFoundError: the closest package name is given when there is one.""",
)
describe(
    "BK627",
    title="a node's source shows a beginner's mistake that rclpy (Jazzy) stops on",
    message={
        "super_init": "{cls}.__init__ never calls super().__init__('node_name'): rclpy raises AttributeError at the first create_...",
        "timer_period": "create_timer({period}, ...) fires every {period} s, not {period} times a second",
        "callback_called": "create_timer is given self.{short}() (its result, None) instead of the method self.{short}",
        "no_self": "{short} is defined without 'self': the timer calls it on the node and it raises TypeError",
        "time_step": "{short} adds {step} to the time at each tick but the timer fires every {period} s: the motion runs {ratio} times its speed",
        "with_node": "'with {cls}() as node:' fails on Jazzy: a Node of rclpy 7.1 is not a context manager",
        "now_not_msg": "header.stamp is given get_clock().now() (an rclpy Time) instead of a message: publishing aborts the process",
        "stamp_seconds": "header.stamp.sec = int(time.time()) leaves nanosec at 0: one distinct stamp a second",
        "shutdown_twice": "rclpy.shutdown() after catching KeyboardInterrupt raises on Jazzy: Ctrl-C already shut the context down",
    },
    hint={
        "super_init": "make super().__init__('node_name') the first line of {cls}.__init__",
        "timer_period": "give the period in seconds: create_timer(1 / {period}, ...) = {hz} s for {period} Hz",
        "callback_called": "pass the method without calling it: create_timer(period, self.{short})",
        "no_self": "define it as def {short}(self):",
        "time_step": "add the timer's period ({period}) at each tick, or read the time from self.get_clock().now()",
        "with_node": "write node = {cls}() then node.destroy_node() at the end",
        "now_not_msg": "write msg.header.stamp = self.get_clock().now().to_msg()",
        "stamp_seconds": "write msg.header.stamp = self.get_clock().now().to_msg(): it fills sec and nanosec",
        "shutdown_twice": "end main() with rclpy.try_shutdown() (or 'if rclpy.ok(): rclpy.shutdown()')",
    },
    explanation="""\
The same mistakes as BK652, seen in the source without running the node: each stops a
beginner's node on ROS 2 Jazzy (rclpy 7.1) with words that do not say the cause, or makes it
move wrongly without any error. Only what the source states literally is judged (a number
written in the call, a method of the same class); a name the reading cannot resolve says
nothing. `bras-kit run` (or `validate --run`) confirms each by running the node.""",
)

# ------------------------------------------------------------------ BK630-BK633 built and launched

describe(
    "BK630",
    title="colcon build stops on this package",
    message={
        "ament_cmake": "package.xml says <build_type>{detail}</build_type>: colcon builds it with CMake and never "
                       "runs setup.py, so urdf/, launch/ and the console_scripts are not installed",
        "marker": "colcon build fails: {colcon}",
        "folder": "colcon build fails: {colcon}",
        "missing_source": "colcon build fails: {colcon}",
        "setup_raised": "colcon build fails, setup.py stops with an error: {colcon}",
        "outside": "data_files installs into {detail}, outside the package's install folder",
        "name": "the package name '{detail}' is not a name colcon accepts: {colcon}",
        "source_outside": "setup() names {source}, outside the package folder: bras-kit does not install it",
        "source_link_out": "setup() names {source}, a symbolic link that leads outside the package folder: "
                           "bras-kit does not install it",
        "source_loop": "setup() names {source}, a loop of symbolic links: bras-kit does not install it",
        "source_device": "setup() names {source}, a device, not a file: bras-kit does not install it",
        "source_fifo": "setup() names {source}, a named pipe, not a file: bras-kit does not install it",
        "source_socket": "setup() names {source}, a socket, not a file: bras-kit does not install it",
        "source_too_large": "setup() names {source}, a file too large to install",
        "module": "'{source}' is not a Python package or module name (dotted identifiers): bras-kit does not "
                  "install it",
        "entry_point": "the console_scripts entry '{source}' is not 'NAME = module:function' with Python names: "
                       "bras-kit writes no script from it",
        "value": "setup() was given {source}, which setuptools does not take there: bras-kit installs nothing "
                 "from it",
        "prefix": "{detail} already exists and is not an install folder colcon made: bras-kit does not remove it",
        "install": "the install tree cannot be laid out: {colcon}",
        "": "colcon build fails: {colcon}",
    },
    hint={
        "ament_cmake": "in package.xml write <build_type>ament_python</build_type> and remove "
                       "<buildtool_depend>ament_cmake</buildtool_depend>, then delete CMakeLists.txt (or recreate "
                       "the package with ros2 pkg create --build-type ament_python {package})",
        "marker": "create the empty file resource/{package} (ros2 pkg create makes it; the ament index needs it)",
        "folder": "{source} is a folder: list its files, e.g. glob('{source}/*')",
        "missing_source": "create {source}, or remove it from data_files (glob('{folder}/*') installs what exists)",
        "setup_raised": "fix setup.py at this line; colcon runs it exactly as python would",
        "outside": "install below share/{package}, e.g. os.path.join('share', package_name, 'urdf')",
        "name": "a package name has lower case letters, digits and underscores and starts with a letter (REP 144), "
                "e.g. name='bras_description', the same in setup.py and package.xml",
        "source_outside": "list only files of the package, relative to its folder, e.g. glob('urdf/*.urdf')",
        "source_link_out": "copy the file into the package instead of linking to it",
        "source_loop": "remove the link, and list the real file",
        "source_device": "list only files of the package, relative to its folder, e.g. glob('urdf/*.urdf')",
        "source_fifo": "list only files of the package, relative to its folder, e.g. glob('urdf/*.urdf')",
        "source_socket": "list only files of the package, relative to its folder, e.g. glob('urdf/*.urdf')",
        "source_too_large": "keep meshes small (decimate them) or leave them out of the package",
        "module": "packages=[package_name] (the folder holding __init__.py), or find_packages(exclude=['test'])",
        "entry_point": "write it as in the tutorial: 'animation = bras_description.animation:main'",
        "value": "compare with the setup.py that ros2 pkg create writes",
        "prefix": "move that folder away, or build into another folder with --install-base",
        "install": "two data_files entries install a file and a folder of the same name: rename one",
        "": "fix setup.py",
    },
    explanation="""\
`colcon build` runs the package's `setup.py` and copies what `data_files` lists into
`install/PKG/`. A source that does not exist stops the copy with setuptools' words ("can't
copy ... doesn't exist or not a regular file"), an exception in `setup.py` stops the build with
its traceback, and a package whose `package.xml` declares `ament_cmake` is built with CMake:
its `setup.py` is ignored (a package made with `ros2 pkg create` without
`--build-type ament_python`, with a `setup.py` pasted in). bras-kit builds the package the same
way, in the sandbox, and stops at the same place.""",
)
describe(
    "BK631",
    title="ros2 launch stops with an error",
    message={
        "": "ros2 launch stops: {ros}",
        "too_many_nodes": "the launch file starts more than 256 nodes: bras-kit evaluates no more, and stops there",
        "log_flood": "the launch file logs more than 10,000 lines or 1 MiB (LogInfo): bras-kit keeps no more, and "
                     "stops there",
    },
    hint={
        "too_many_nodes": "the tutorial's launch file starts 3 nodes: look for a loop that adds Node(...) actions",
        "log_flood": "the tutorial's launch file logs nothing: look for a loop that adds LogInfo(...) actions",
        "package": "no installed package is called '{missing}': use the name in package.xml ('{known}'), then "
                   "colcon build and source install/setup.bash",
        "package_near": "no installed package is called '{missing}': did you mean '{near}'?",
        "executable": "the package's executables are its console_scripts names ({names}): use one of them, or add "
                      "'{executable} = PACKAGE.MODULE:main' to console_scripts and build again",
        "executable_py": "an executable has no .py: write executable='{fixed}' (the console_scripts name)",
        "relative": "ros2 launch runs from the folder you type it in, not from the package: build the path from the "
                    "installed share folder, {fixed}",
        "not_installed": "{path} exists in the package but setup.py does not install it: add its folder to "
                         "data_files, then colcon build",
        "no_file": "no file {path} in the package: check the folder and file name",
        "yaml": "read as YAML, the URDF text fails: wrap it, ParameterValue(Command(['xacro ', path]), value_type=str) "
                "(from launch_ros.parameter_descriptions import ParameterValue)",
        "yaml_rules": "a parameter without a type is read with YAML rules, and the URDF text is not YAML ({reason}, "
                      "line {text_line} of the text): keep it as text with {fix}",
        "attribute_missing": "launch's XML and YAML files name it {attribute}, not {written}: write {fix}",
        "attribute_renamed": "launch's XML and YAML files use other names than Python: write {fix}",
        "attribute_unexpected": "{attributes} is not read on {entity}: remove it or check its name in the "
                                "launch file format (docs.ros.org, Launch file format)",
        "tag_unknown": "{tag} is not a tag launch reads (tags are lower case: node, include, group, arg, let, "
                       "executable, timer...)",
        "include_dict": "launch_arguments takes (name, value) pairs: write launch_arguments={{...}}.items()",
        "parameters_not_list": "parameters takes a list of dicts: parameters=[{{'robot_description': description}}]",
        "not_a_list": "LaunchDescription takes a list of actions: LaunchDescription([...]), not one {given}",
        "not_text": "launch values are text or substitutions, not {given}: write it in quotes (default_value='true')",
        "no_generate": "ros2 launch calls generate_launch_description(): define a function of that name that "
                       "returns LaunchDescription([...])",
        "no_description": "generate_launch_description() returns {returned}: end it with "
                          "return LaunchDescription([...])",
        "": "the launch file stops at this line; fix it and launch again",
    },
    explanation="""\
`ros2 launch` loads the launch file, calls `generate_launch_description()` and evaluates every
action and substitution before starting the nodes. An exception on the way stops the launch with
"Caught exception in launch": a package that is not installed (`get_package_share_directory`,
`FindPackageShare`: PackageNotFoundError), a file opened by a path relative to the current
folder, a file that `setup.py` does not install, an executable that is not a console_scripts
name, a URDF given to a parameter through a substitution without `ParameterValue(...,
value_type=str)` (or, in XML and YAML, without `type="str"`: launch then reads the text with
YAML rules and stops on "Failed to convert ... using yaml rules" when it is not YAML), an XML or
YAML attribute written with its Python name (`executable` for `exec`: "Can not find attribute
'exec' in Entity 'node'"), `launch_arguments` given as a dict instead of `dict.items()` ("too
many values to unpack"), a `generate_launch_description()` that returns no LaunchDescription.
bras-kit evaluates the launch file the same way against a stand-in of launch, launch_ros and
ament_index_python (Jazzy) and reports the line it stopped at.""",
)
describe(
    "BK632",
    title="robot_state_publisher cannot load robot_description",
    message={
        "empty": "robot_state_publisher stops: {ros}",
        "file_missing": "robot_state_publisher stops: {ros}",
        "file_refused": "robot_state_publisher is given {detail} as its URDF file: a device, a pipe, a link out of "
                        "the package or a file outside it, which bras-kit does not read",
        "path": "robot_description is a file's path, not its text: {ros}",
        "xacro": "robot_description is xacro source that xacro never expanded: {ros}",
        "not_urdf": "robot_description is not a URDF robot ({detail}): {ros}",
        "too_large": "robot_description is {detail} MiB of text, more than the 8 MiB bras-kit reads: the robot is "
                     "neither checked nor shown",
        "too_many": "robot_description declares more than {detail} links and joints, more than bras-kit holds: the "
                    "robot is neither checked nor shown",
        "": "robot_state_publisher stops: {ros}",
    },
    hint={
        "empty": "give the URDF text: parameters=[{{'robot_description': description}}] with description read from "
                 "the installed urdf/ file",
        "file_missing": "install the URDF (data_files) and pass its text as the robot_description parameter",
        "file_refused": "read the robot from the package's installed urdf/ file: "
                        "os.path.join(get_package_share_directory(PACKAGE), 'urdf', 'bras.urdf')",
        "path": "pass the file's text: with open(path) as f: description = f.read(), then "
                "{{'robot_description': description}}",
        "xacro": "run xacro on it: ParameterValue(Command(['xacro ', path]), value_type=str), or "
                 "xacro.process_file(path).toxml()",
        "not_urdf": "check the file the launch file reads: it must be the robot's URDF",
        "too_large": "the tutorial's arm is 5 kB: check that the launch file reads the robot's URDF file, and only it",
        "too_many": "the tutorial's arm has 3 links: check that the launch file reads the robot's URDF file, and only "
                    "it",
        "": "give robot_state_publisher the URDF text",
    },
    explanation="""\
robot_state_publisher reads the robot from its `robot_description` parameter, a string holding
the whole URDF (robot_state_publisher.cpp). An empty string stops it ("robot_description
parameter must not be empty"), a path or a `.xacro` source fails to parse ("Unable to initialize
urdf::model from robot description"): no TF, no model, an empty RViz. The text must be the URDF
itself: read the installed file, or run xacro in the launch file.""",
)
describe(
    "BK634",
    title="a launched node dies on its ROS arguments",
    message={
        "unknown_ros_args": "{node} dies as it starts: {ros}",
        "invalid_ros_args": "{node} dies as it starts: {ros}",
        "": "{node} dies as it starts: {ros}",
    },
    hint={
        "unknown_ros_args": "one list item per word: ros_arguments=[{fixed}] (in XML, ros_args=\"--log-level warn\" "
                            "without inner quotes)",
        "": "check the ROS arguments: -r FROM:=TO, -p NAME:=VALUE, --params-file FILE, --log-level LEVEL",
    },
    explanation="""\
A node reads its ROS arguments with rcl's rules (rcl/src/rcl/arguments.c): after `--ros-args`
each flag (`--log-level`, `-r`, `-p`, `--params-file`) and its value are separate words. Given
`ros_arguments=['--log-level warn']`, the node receives one word `--log-level warn`, which is
no ROS flag: rclpy.init and rclcpp::init stop with UnknownROSArgsError and the process dies,
while the rest of the launch goes on without it. In XML, `ros_args="--log-level warn"` is split
into two words and works.""",
)
describe(
    "BK635",
    title="an event handler waits for a process that never starts",
    message="OnProcessStart waits for {target}, which this launch never starts: {waiting} never starts either",
    hint="put that very Node in the LaunchDescription (the handler matches the same object), or start {waiting} "
         "without the handler",
    explanation="""\
`RegisterEventHandler(OnProcessStart(target_action=rsp, on_start=[rviz]))` starts RViz when the
action `rsp` has started, and only then: launch matches the started process by identity
(event_handlers/on_action_event_base.py). When `rsp` is never put in the LaunchDescription (a
second `Node(...)` is not the same object), or its condition is false, the event never happens and
RViz never opens, without any error from ros2 launch.""",
)
describe(
    "BK633",
    title="urdf/ or launch/ is inside the Python module folder",
    message="{package}/{folder}/ is inside the module folder: setup.py's glob('{folder}/*') looks in the package "
            "folder and installs nothing",
    hint="move the folder one level up, beside setup.py and package.xml: mv {package}/{folder} {folder}",
    explanation="""\
`ros2 pkg create --build-type ament_python PKG` makes `PKG/PKG/` for the Python code; the
tutorial's `mkdir urdf launch` is typed in the package folder, beside `setup.py`. Made inside
the module folder, the files are not where `data_files` looks (`glob('urdf/*.urdf')` is relative
to `setup.py`), nothing is installed, and `ros2 launch` fails with file not found.""",
)
describe(
    "BK628",
    title="the console scripts will not be installed in lib/PKG",
    message={
        "missing": "setup.cfg is missing: colcon installs {scripts} in install/{package}/bin/, and "
                   "'ros2 run {package} {executable}' says No executable found",
        "no_key": "setup.cfg has no [install] install_scripts: colcon installs {scripts} in install/{package}/bin/, "
                  "and 'ros2 run {package} {executable}' says No executable found",
        "elsewhere": "setup.cfg installs the scripts in {value}, not {target}: 'ros2 run {package} {executable}' "
                     "says No executable found",
        "unparsed": "setup.cfg cannot be read as setuptools reads it: {detail}",
    },
    hint={
        "elsewhere": "write install_scripts=$base/lib/{package} under [install] (and script_dir=$base/lib/{package} "
                     "under [develop]), then run colcon build again",
        "unparsed": "fix this line: setuptools stops on it during colcon build",
        "": "write a setup.cfg beside setup.py with [develop] script_dir=$base/lib/{package} and [install] "
            "install_scripts=$base/lib/{package} ('bras-kit new' shows one), then run colcon build again",
    },
    explanation="""\
`ros2 run PKG EXE` only looks in `install/PKG/lib/PKG/`. The console scripts that `setup.py`
declares land there because `setup.cfg` says so: colcon reads `[install] install_scripts`
and hands it to setuptools on the command line (colcon-core `task/python/build.py`, lines
37-49 and 125-131). When the key is missing, or names another folder (a package copied and
renamed keeps the old name here), setuptools uses its own default, `install/PKG/bin/`. The
build reports success, and only `ros2 run` fails, with "No executable found". A launch file's
`Node(executable=...)` fails the same way.""",
)
describe(
    "BK629",
    title="setup.cfg uses a dash-separated key",
    message="'{key}' in [{section}]: setuptools warns Usage of dash-separated '{key}' will not be supported in "
            "future versions. Please use the underscore name '{underscore}' instead",
    hint="write {underscore} instead of {key}",
    explanation="""\
Older package templates wrote `script-dir` and `install-scripts`. setuptools still reads such
keys in its own sections (`metadata`, `options`, and its commands such as `develop` and
`install`), turning the dash into an underscore, but prints a SetuptoolsDeprecationWarning on
every build (setuptools 68.1.2, Ubuntu 24.04's: `setuptools/dist.py`, `warn_dash_deprecation`,
lines 770-802; newer releases word it "Invalid dash-separated key"). Its release 78.0.0
refused them outright for a few days, and a later release may do so again: with the underscore
names the package builds the same, without the warning.""",
)
