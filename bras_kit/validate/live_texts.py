"""The English words of the live rules (BK8xx). French: ``validate.po`` (msgctxt = code)."""

from __future__ import annotations

from ..findings.registry import Plural, describe

describe(
    "BK800",
    title="no ROS 2 node is seen on this domain",
    message={
        "domain": Plural(
            "no node on ROS_DOMAIN_ID {domain}, but {nodes} runs on domain {other}: this terminal and theirs are on different domains",
            "no node on ROS_DOMAIN_ID {domain}, but {nodes} run on domain {other}: this terminal and theirs are on different domains",
            "nodes"),
        "range": Plural(
            "no node on ROS_DOMAIN_ID {domain} with discovery range {ours}, but {nodes} is seen with range {other}: the terminals do not search the same way",
            "no node on ROS_DOMAIN_ID {domain} with discovery range {ours}, but {nodes} are seen with range {other}: the terminals do not search the same way",
            "nodes"),
        "": "no ROS 2 node on ROS_DOMAIN_ID {domain} (watched {seconds} s), nor on another domain of this computer",
    },
    hint={
        "domain": "type '{command}' in this terminal (or the same ROS_DOMAIN_ID in every terminal), then run again",
        "range": "type '{command}' in this terminal (or the same setting in every terminal), then run again",
        "": "start the tutorial's launch file in another terminal (ros2 launch bras_description "
            "affichage.launch.py), with the same ROS_DOMAIN_ID, then run again",
    },
    explanation="""\
ROS 2 nodes only see the nodes of their own domain (`ROS_DOMAIN_ID`, 0 when unset) that search
for each other the same way (`ROS_AUTOMATIC_DISCOVERY_RANGE`: `LOCALHOST` keeps to this
computer, `SUBNET` is the default). Two terminals set differently each see an empty graph: RViz
in one shows nothing of what the other publishes. When this domain is empty, `doctor --ros`
looks at the domains other processes of this computer use and tries the other discovery range,
and names the setting that finds the nodes.""",
)
describe(
    "BK801",
    title="nothing publishes /robot_description",
    message={
        "near": "nothing publishes /robot_description, but {topic} is published by {nodes}: RViz's RobotModel "
                "reads /robot_description unless its Description Topic says otherwise",
        "readers": Plural(
            "nothing publishes /robot_description, yet {readers} waits for it: RViz stays empty (\"Waiting for robot_description...\" is not a hang: nothing will come)",
            "nothing publishes /robot_description, yet {readers} wait for it: RViz stays empty (\"Waiting for robot_description...\" is not a hang: nothing will come)",
            "readers"),
        "": "nothing publishes /robot_description (nodes seen: {nodes}): RViz's RobotModel has no robot to show",
    },
    hint={
        "near": "set the RobotModel's Description Topic to {topic} in RViz, or start robot_state_publisher "
                "without the namespace or remapping that moved it",
        "": "start robot_state_publisher with the URDF as its robot_description parameter: the tutorial's "
            "launch file does it (ros2 launch bras_description affichage.launch.py)",
    },
    explanation="""\
RViz's RobotModel display reads the robot from the topic `/robot_description`, which
robot_state_publisher publishes from its `robot_description` parameter. When it is not running
(or crashed at start: look at its terminal), RViz stays empty and RobotModel shows a warning.""",
)
describe(
    "BK802",
    title="/robot_description is published volatile",
    message="{node} publishes /robot_description volatile: a reader started after it (RViz) never gets it",
    hint="publish it with QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL), as "
         "robot_state_publisher does, or let robot_state_publisher publish it",
    explanation="""\
robot_state_publisher publishes the description once, reliable and *transient local*
(src/robot_state_publisher.cpp:133-135 in Jazzy's 3.3): the middleware keeps the last message
for readers that join later, like RViz opened after the launch. A description published
*volatile* reaches only the readers present at that instant; a transient-local reader (RViz's
RobotModel) does not even match it. The model stays empty, with no error.""",
)
describe(
    "BK803",
    title="/robot_description is published but nothing was received",
    message=Plural(
        "{nodes} publishes /robot_description, but no text came in {seconds} s",
        "{nodes} publish /robot_description, but no text came in {seconds} s",
        "nodes"),
    hint="restart the node that publishes it; if it publishes by hand, publish with transient_local "
         "durability so that late readers get it",
    explanation="""\
A publisher of `/robot_description` is in the graph, but no message reached a reliable,
transient-local reader (what RViz is) while `doctor --ros` watched. The publisher has not
published yet, or published once long ago without keeping the message.""",
)
describe(
    "BK804",
    title="/robot_description is not a URDF",
    message={
        "path": "/robot_description holds a file name, '{text}', not the URDF itself: RViz cannot read a path",
        "empty": "/robot_description is empty: RViz has no robot to show",
        "other": "/robot_description is not XML ('{text}'): RViz cannot read it as a URDF",
        "": "/robot_description is not a URDF",
    },
    hint={
        "path": "give robot_state_publisher the file's contents: robot_desc = open(urdf_path).read(), then "
                "parameters=[{{'robot_description': robot_desc}}] (the tutorial's launch file)",
        "empty": "read the URDF file in the launch file and pass its text as robot_description",
        "": "pass the URDF's text as robot_description",
    },
    explanation="""\
The `robot_description` parameter of robot_state_publisher is the URDF *text*. A launch file
that passes the path (`parameters=[{'robot_description': urdf_path}]`) or an empty string
publishes that on `/robot_description`; RViz's RobotModel cannot parse it and stays empty.
The tutorial's launch file reads the file first: `open(urdf_path).read()`.""",
)
describe(
    "BK810",
    title="nothing publishes /joint_states",
    message={
        "near": "nothing publishes /joint_states, but {topic} is published by {nodes}: robot_state_publisher "
                "reads /joint_states only, the arm does not move",
        "links": "nothing publishes /joint_states: robot_state_publisher publishes no transform for the moving "
                 "links, RViz says \"No transform from [{link}] to [{root}]\" and the arm does not move",
        "": "nothing publishes /joint_states: the arm does not move",
    },
    hint={
        "near": "publish on 'joint_states' (self.create_publisher(JointState, 'joint_states', 10)), in the "
                "namespace of robot_state_publisher",
        "": "start the slider window (ros2 run joint_state_publisher_gui joint_state_publisher_gui) or your "
            "node (ros2 run bras_description animation), in a terminal with the same ROS_DOMAIN_ID",
    },
    explanation="""\
robot_state_publisher turns the angles it receives on `/joint_states` into the transforms of the
moving links. With nobody publishing them, only the fixed links have a transform: RViz draws
them and says "No transform from [avant_bras] to [base]" for the others. The tutorial's pitfall
"Le robot apparaît mais ne bouge pas": check that a source publishes on /joint_states.""",
)
describe(
    "BK811",
    title="several nodes publish /joint_states",
    message={
        "slider": Plural(
            "{n} node publishes /joint_states ({nodes}): the slider window ({slider}) and your node take turns, the arm jumps between their angles",
            "{n} nodes publish /joint_states ({nodes}): the slider window ({slider}) and your node take turns, the arm jumps between their angles",
            "n"),
        "": Plural(
            "{n} node publishes /joint_states ({nodes}): robot_state_publisher takes each message in turn and the arm jumps between them",
            "{n} nodes publish /joint_states ({nodes}): robot_state_publisher takes each message in turn and the arm jumps between them",
            "n"),
    },
    hint={
        "slider": "close the slider window, as the tutorial says before running the animation node",
        "": "keep one publisher of /joint_states (or give them different joints)",
    },
    explanation="""\
robot_state_publisher uses every message it receives on `/joint_states`. With the slider window
and the animation node both running, each resets the arm to its own angles many times a second:
the arm flickers. The tutorial says to close the slider window before `ros2 run bras_description
animation`.""",
)
describe(
    "BK812",
    title="/joint_states has publishers but no message came",
    message={
        "type": "/joint_states carries {types} from {nodes}, not sensor_msgs/msg/JointState: "
                "robot_state_publisher cannot read it, the arm does not move",
        "sim": Plural(
            "{nodes} publishes /joint_states but sent nothing in {seconds} s: {sim_use}",
            "{nodes} publish /joint_states but sent nothing in {seconds} s: {sim_use}",
            "nodes"),
        "": Plural(
            "{nodes} publishes /joint_states but sent nothing in {seconds} s: the arm does not move",
            "{nodes} publish /joint_states but sent nothing in {seconds} s: the arm does not move",
            "nodes"),
    },
    hint={
        "type": "publish sensor_msgs.msg.JointState on /joint_states (from sensor_msgs.msg import JointState), "
                "with the URDF's joint names in msg.name",
        "sim": "set use_sim_time to false (or start what publishes /clock)",
        "": "make sure the node's timer runs: rclpy.spin(node) after creating it, and a timer callback that "
            "calls publish",
    },
    parts={
        "sim_use": Plural(
            "{sim} uses simulated time and nothing publishes /clock, so its timer never fires",
            "{sim} use simulated time and nothing publishes /clock, so their timers never fire",
            "sim"),
    },
    explanation="""\
A node created a publisher on `/joint_states` but no message reached `doctor --ros` while it
watched: its timer is not running (no `rclpy.spin`), or waits for a clock that never ticks
(`use_sim_time` true without `/clock`), or the node publishes only when something else happens.""",
)
describe(
    "BK813",
    title="/joint_states comes slower than the tutorial's 20 Hz",
    message="/joint_states comes at {rate} Hz (one message every {period} s), not the tutorial's {expected} Hz: "
            "the arm moves in visible steps",
    hint="create the timer with a period of 0.05 s: self.create_timer(0.05, self.tick)",
    explanation="""\
The tutorial's node publishes twenty times a second (`create_timer(0.05, ...)`), enough for a
smooth motion in RViz. The rate is measured over the messages received while `doctor --ros`
watched (all publishers together). The slider window publishes at 10 Hz by design and is not
checked.""",
)
describe(
    "BK814",
    title="/joint_states messages are stamped zero",
    message={
        "all": "every /joint_states message ({total}) has header.stamp = 0: robot_state_publisher 3.3 publishes "
               "no transform for them, the arm does not move",
        "some": Plural(
            "{count} of {total} /joint_states messages has header.stamp = 0: robot_state_publisher skips it",
            "{count} of {total} /joint_states messages have header.stamp = 0: robot_state_publisher skips them",
            "count"),
    },
    hint="stamp each message: msg.header.stamp = self.get_clock().now().to_msg()",
    explanation="""\
robot_state_publisher publishes a joint's transform only when the message's stamp is at least
one publish period after the last one it used for that joint; a joint seen for the first time
counts from time zero (src/robot_state_publisher.cpp:324-340 in Jazzy's 3.3). A stamp of zero is
never after zero plus a period: nothing is published, RViz says "No transform" and the arm stays
still. The tutorial's node stamps each message with `self.get_clock().now().to_msg()`.""",
)
describe(
    "BK815",
    title="/joint_states stamps are far from this computer's clock",
    message={
        "behind": "/joint_states messages are stamped {seconds} s before this computer's clock: RViz still "
                  "draws the latest transforms, but what looks them up at the current time fails",
        "ahead": "/joint_states messages are stamped {seconds} s after this computer's clock: RViz may "
                 "wait for them or drop them",
    },
    hint="stamp with the node's clock, self.get_clock().now().to_msg(), and keep every node on the same time "
         "(use_sim_time on all of them or on none)",
    explanation="""\
The transforms robot_state_publisher publishes carry the stamp of the joint states. tf2 keeps
the latest of each frame however old (tf2/src/cache.cpp:255-290 prunes by the newest it holds,
not by the clock), and RViz's RobotModel asks for the latest (rviz_common frame_manager.cpp,
SyncOff): old stamps that advance still move the arm. What asks for the current time (a tf2
lookup in a node, RViz's displays in synchronised modes) gets an "extrapolation" error. A stamp
made by hand (a counter, a clock of another machine) or simulated time on only some of the nodes
cause it.""",
)
describe(
    "BK816",
    title="/joint_states names a joint that the URDF cannot move",
    message={
        "near": "/joint_states names '{joint}', which is not a movable joint of /robot_description: did you "
                "mean '{near}'?",
        "fixed": "/joint_states names '{joint}', a fixed joint: robot_state_publisher ignores it",
        "": "/joint_states names '{joint}', which is not a joint of /robot_description (its movable joints: "
            "{movable})",
    },
    hint={
        "near": "write '{near}' in msg.name, exactly as in the URDF",
        "fixed": "leave '{joint}' out of msg.name",
        "": "use the URDF's joint names in msg.name: {movable}; if you have just added '{joint}' to the URDF, "
            "rebuild (colcon build) and start the launch again: the robot_state_publisher running still has "
            "the old file",
    },
    explanation="""\
robot_state_publisher looks each name of a JointState up in the URDF and silently skips the
ones it does not know (ROS 2 prints no warning). The joint meant keeps no transform and RViz
says "No transform" for its link, or draws it where it was.""",
)
describe(
    "BK817",
    title="a movable joint of the URDF is never in /joint_states",
    message="joint '{joint}' is never in /joint_states (names received: {seen}): robot_state_publisher "
            "publishes no transform for '{link}', which RViz cannot place",
    hint="add '{joint}' to msg.name with its position (every movable joint, in every message or in turn)",
    explanation="""\
robot_state_publisher publishes the transform of a moving link only once it has received its
joint's position. A joint left out of every message leaves its link, and all below it, without a
transform: RViz says "No transform from [avant_bras] to [base]".""",
)
describe(
    "BK818",
    title="/joint_states positions are past the joint limits",
    message={
        "degrees": "joint '{joint}' reaches {value}, a number of degrees: read as radians it is past its "
                   "limit {bound}, as degrees ({radians} rad) it is within {lower}..{upper} rad",
        "upper": "joint '{joint}' reaches {value} rad, {excess} rad above its upper limit {bound}",
        "lower": "joint '{joint}' reaches {value} rad, {excess} rad below its lower limit {bound}",
    },
    hint={
        "degrees": "send radians, as JointState and the URDF mean them: math.radians(angle)",
        "": "stay within {lower}..{upper} rad (the <limit> of the URDF), or widen the limit if the mechanism "
            "allows it",
    },
    explanation="""\
robot_state_publisher draws any angle it receives, even past the `<limit>` of the URDF: RViz
shows the arm through itself. A real arm or a controller would stop at the limit. The tutorial's
pitfall "Les articulations dépassent".""",
)
describe(
    "BK819",
    title="/joint_states messages have more names than positions, or fewer",
    message={
        "empty": Plural(
            "{count} of {total} /joint_states messages has {name_count} and no position: robot_state_publisher ignores it",
            "{count} of {total} /joint_states messages have {name_count} and no position: robot_state_publisher ignores them",
            "count"),
        "": Plural(
            "{count} of {total} /joint_states messages has {name_count} but {position_count}: robot_state_publisher ignores it",
            "{count} of {total} /joint_states messages have {name_count} but {position_count}: robot_state_publisher ignores them",
            "count"),
    },
    hint="give msg.position one value per name, in the same order",
    parts={
        "name_count": Plural("{names} name", "{names} names", "names"),
        "position_count": Plural("{positions} position", "{positions} positions", "positions"),
    },
    explanation="""\
robot_state_publisher ignores a JointState whose `name` and `position` lists differ in length
(src/robot_state_publisher.cpp:303-312 in Jazzy's 3.3), with one line in its log.""",
)
describe(
    "BK820",
    title="a publisher and a subscription cannot match (QoS)",
    message={
        "durability": "{publisher} publishes volatile and {subscriber} reads transient_local: they never "
                      "connect, {subscriber} receives nothing (rclpy: {reason})",
        "reliability": "{publisher} publishes best effort and {subscriber} reads reliable: they never connect, "
                       "{subscriber} receives nothing (rclpy: {reason})",
        "": "{publisher} ({offered}) and {subscriber} ({requested}) cannot connect, policies {policies} "
            "(rclpy: {reason})",
    },
    hint={
        "durability": "publish transient_local (as robot_state_publisher does), or read volatile",
        "reliability": "publish reliable, or read best effort",
        "": "give both ends compatible QoS settings",
    },
    explanation="""\
A subscription receives only from publishers whose QoS offers at least what it asks: a reader
asking *transient local* does not match a *volatile* publisher, a *reliable* reader does not
match a *best effort* publisher. Nothing reports it but a warning in the reader's log; the
check is rmw's own (`rclpy.qos.qos_check_compatible`, as `ros2 doctor` uses), run where the
probe runs, and the finding names the policies in rclpy's own words.""",
)
describe(
    "BK830",
    title="a node uses simulated time but nothing publishes /clock",
    message="{node} has use_sim_time = true but nothing publishes /clock: its clock stays at zero, its "
            "timers never fire and its stamps are zero",
    hint="ros2 param set {node} use_sim_time false (or drop use_sim_time from the launch file), unless a "
         "simulator or 'ros2 bag play --clock' is meant to run",
    explanation="""\
With `use_sim_time` true a node reads its time from `/clock` (a simulator, `ros2 bag play
--clock`). Without anything on `/clock` its time stays at zero: its timers never fire and what it
stamps is stamped zero, so robot_state_publisher publishes no transform and the arm stays still.""",
)
describe(
    "BK840",
    title="robot_state_publisher turns almost none of /joint_states into transforms",
    message={
        "stops": "robot_state_publisher stops turning /joint_states into transforms {after} s into the watch, "
                 "though messages keep coming for {seconds} s ({dropped} dropped: {reason}): RViz's arm stops there",
        "stamp": "robot_state_publisher turns {published} of the {received} /joint_states messages into "
                 "transforms, their stamps do not advance ({reason}): RViz's arm stays still",
        "": "robot_state_publisher turns {published} of the {received} /joint_states messages into "
            "transforms ({reason}): RViz's arm stays still",
    },
    hint={
        "stops": "stamp with the current time; after stamps go back (a bag played in a loop, a counter "
                 "restarted), restart robot_state_publisher, which keeps the newest stamp it used",
        "stamp": "stamp each message when it is sent: msg.header.stamp = self.get_clock().now().to_msg()",
        "": "send messages robot_state_publisher takes: the URDF's joint names, one position each, "
            "stamped with self.get_clock().now().to_msg()",
    },
    explanation="""\
`doctor --ros` hands every JointState it received to a model of robot_state_publisher 3.3.3
(`callbackJointState`, src/robot_state_publisher.cpp:300-363). A message goes out as transforms
only when its stamp is at least one publish interval (50 ms at the default 20 Hz) after the
stamp last used for its joints. A stamp made once and reused, or one that is set only at the
start, passes the first time and never again: the arm RViz draws stays where the first message
put it, however the angles change.""",
)
describe(
    "BK841",
    title="/joint_states carries NaN or infinite positions",
    message={
        "never": "{count} of {total} /joint_states messages give '{joint}' = {value}: tf2 refuses the transform "
                 "of '{link}' (TF_NAN_INPUT) and RViz cannot place it ({rviz})",
        "": "{count} of {total} /joint_states messages give '{joint}' = {value}: tf2 refuses the transform of "
            "'{link}' (TF_NAN_INPUT) and RViz keeps it at its last valid angle",
    },
    hint="give '{joint}' a finite angle in radians (check the computation: a division by zero, math.acos "
         "of a value past 1, an unset variable)",
    explanation="""\
robot_state_publisher does not check the values it receives: it computes the transform and
publishes it. tf2 refuses every transform holding a NaN (tf2/src/buffer_core.cpp:235-243, error
TF_NAN_INPUT); an infinite angle gives NaN once turned into a rotation. RViz keeps the link at the
last transform it accepted, or cannot place it at all when none came.""",
)
describe(
    "BK842",
    title="/joint_states stopped during the watch",
    message={
        "left": "the last /joint_states message came {seconds} s before the end of the watch ({after} s into "
                "it, {sent}) and nothing publishes /joint_states any more: its node stopped or "
                "crashed, RViz's arm is still",
        "": "the last /joint_states message came {seconds} s before the end of the watch ({after} s into it, "
            "{sent}): its node stopped publishing, RViz's arm is still",
    },
    parts={"sent": Plural("{count} message", "{count} messages", "count")},
    hint={
        "left": "look at the node's terminal for its error (a traceback ends the node), fix it and start it again",
        "": "look at the node's timer and its terminal: it publishes no more",
    },
    explanation="""\
The messages came at first, then stopped before `doctor --ros` finished watching. When the
publisher is also gone from the graph, its process ended (an exception in a callback ends
`rclpy.spin`). RViz keeps the arm at the last transforms it received.""",
)
describe(
    "BK843",
    title="robot_state_publisher moves RViz's arm in steps",
    message="robot_state_publisher turns only {moves} of the {received} /joint_states messages into transforms "
            "({rate} a second): the stamps advance in steps of {step} s, and it waits one publish interval "
            "between two stamps",
    hint="stamp with the full time, seconds and nanoseconds: msg.header.stamp = self.get_clock().now().to_msg()",
    explanation="""\
robot_state_publisher publishes a joint's transform only when the stamp is at least one publish
interval newer than the last it published for that joint (src/robot_state_publisher.cpp:334-340).
Stamps that advance in steps (whole seconds, a counter) let through one message per step: the
arm RViz draws jumps from pose to pose.""",
)
describe(
    "BK844",
    title="several nodes share one name",
    message="{count} nodes are named {node}: the graph cannot tell them apart, their parameters, services "
            "and logs mix",
    hint="stop the copy left running (a launch still open in another terminal), or give each node a name of "
         "its own (name='...' in the launch file)",
    explanation="""\
ROS 2 lets two nodes bear the same name and only warns in their logs. Tools that address a node
by its name (`ros2 param`, `ros2 node info`, the parameter services) reach one of them at random.
A second launch started before the first was stopped gives two robot_state_publishers, each
publishing its own transforms.""",
)
describe(
    "BK845",
    title="/robot_description carries two different robots",
    message={
        "names": "/robot_description carries {n} different robots, from {nodes} (they differ in {names}): RViz "
                 "shows whichever came last, and each robot_state_publisher publishes its own transforms",
        "": "/robot_description carries {n} different robots, from {nodes}: RViz shows whichever came last, and "
            "each robot_state_publisher publishes its own transforms",
    },
    hint="stop the old launch (Ctrl-C in its terminal), rebuild the package (colcon build) and start the launch "
         "once",
    explanation="""\
Each robot_state_publisher publishes its URDF on `/robot_description`, kept for late readers
(transient local). With two of them running, from an old launch and a new one, a reader gets
both and keeps the one that reached it last: RViz may show the old arm, and the joint names of
the new one look unknown. Which one wins changes from run to run.""",
)
describe(
    "BK846",
    title="RViz's Fixed Frame is no frame of the robot",
    message={
        "argument": "rviz2 (process {pid}) was started with -f {frame}, which is no link of the robot: RViz's Global "
                    "Status says \"Frame [{frame}] does not exist\" and it draws no link",
        "file": "RViz's Fixed Frame is {frame} ({path}, the -d file of rviz2, process {pid}), which is no link of "
                "the robot: RViz's Global Status says \"Frame [{frame}] does not exist\" and it draws no link",
        "home": "RViz's Fixed Frame is {frame} ({path}, which rviz2 loads without -d, process {pid}), which is no "
                "link of the robot: RViz draws no link",
        "launch": "the rviz2 of {launch} would open with Fixed Frame {frame} (from {path}), which is no link of the "
                  "robot: RViz's Global Status would say \"Frame [{frame}] does not exist\" and it would draw no link",
        "": "rviz2 (process {pid}) opens with RViz's default Fixed Frame, {frame}, which is no link of the robot: "
            "until it is set in RViz's window, RViz draws no link",
    },
    hint={
        "argument": "start rviz2 with -f {root}, or without -f",
        "file": "write Fixed Frame: {root} under Global Options in {path} (or set it in RViz and File > Save Config)",
        "home": "set Fixed Frame to {root} in RViz (Global Options), then File > Save Config",
        "launch": "write Fixed Frame: {root} under Global Options in the .rviz of the launch (or drop its -f), then "
                  "colcon build",
        "": "set Fixed Frame to {root} in RViz (Global Options), then File > Save Config to keep it",
    },
    explanation="""\
RViz draws each link where tf2 places it in the Fixed Frame. rviz2 takes that frame from `-f`,
else from the `-d` file (Global Options > Fixed Frame), else from `~/.rviz2/default.rviz`, else
from its own default, `map` (ros2/rviz jazzy: visualizer_app.cpp:95-103 and 165-169,
visualization_frame.cpp:345-349, default.rviz:54). bras-kit reads the command line of the
rviz2 running on this machine with this ROS_DOMAIN_ID; a frame chosen in RViz's window after it
started is not seen from outside.""",
)
describe(
    "BK847",
    title="what changed on the graph during the watch",
    message={
        "joined": "{at} s: {node} joined the graph",
        "left": "{at} s: {node} left the graph",
        "publishes": "{at} s: {node} began publishing {topic}",
        "unpublishes": "{at} s: {node} stopped publishing {topic}",
        "replaced": "{at} s: a new description arrived on /robot_description (text {n}): RViz shows it from then on",
        "silent": "{at} s: the last /joint_states message; still published by {nodes}, who send nothing",
        "silent-left": "{at} s: the last /joint_states message; nothing publishes it any more",
    },
    hint="",
    explanation="""\
The timeline of the watch, in seconds from its start: the nodes that joined or left, the
publishers of /robot_description and /joint_states that came or went, a description replaced,
and the last joint state when they stopped coming. Nodes found while discovery was still
finding the first ones (2.5 s) were there from the start.""",
)
