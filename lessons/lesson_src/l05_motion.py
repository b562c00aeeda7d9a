"""Lesson 5: command by program: the sine motion, waypoints, a GIF, the angle plot."""

from ._cells import Lesson, code, md

LESSON = Lesson(
    "05",
    {"fr": "commander-par-programme", "en": "command-by-program"},
    {"fr": "5 · Commander par programme", "en": "5 · Command by program"},
)

LESSON.cells = [
    md(
        """
        À l'étape 7 du tutoriel, un nœud remplace les curseurs : 20 fois par seconde, il publie
        un message `JointState` (des noms d'articulations et des angles) sur `/joint_states`. Les angles
        viennent de deux sinusoïdes : `epaule = 0.8 sin t` et `coude = 1.2 sin 0.7t`.

        Un **programme de mouvement** est juste cela : une fonction du temps vers les angles.
        `bras_kit.motion` les écrit, les échantillonne comme le nœud, et vérifie les butées.
        """,
        """
        In the tutorial's step 7 a node replaces the sliders: 20 times a second it publishes a
        `JointState` message (joint names and angles) on `/joint_states`. The angles come from two
        sine waves: `epaule = 0.8 sin t` and `coude = 1.2 sin 0.7t`.

        A **motion program** is just that: a function from time to angles. `bras_kit.motion`
        writes them, samples them the way the node does, and checks the limits.
        """,
    ),
    code(
        """
        import numpy as np
        from IPython.display import Image, display

        import bras_kit
        from bras_kit.motion import check_limits, formula_motion, sample, tutorial_motion, waypoint_motion

        bras_kit.set_language("@LANG@")  # the library's messages and picture words in this notebook's language
        robot = bras_kit.arm()
        motion = tutorial_motion(robot)
        states = sample(motion, duration=10.0, rate=20.0)  # 20 Hz, like the node's 0.05 s timer
        print(states.names, states.positions.shape)
        for t, (epaule, coude) in zip(states.times[:5], states.positions[:5]):
            print(f"t={t:4.2f}  epaule={epaule:+.3f}  coude={coude:+.3f}")
        """
    ),
    md(
        """
        Chaque ligne est ce qu'un message `JointState` aurait contenu. Vérifions la formule :
        """,
        """
        Each row is what one `JointState` message would have carried. Check the formula:
        """,
    ),
    code(
        """
        t = states.times
        assert np.allclose(states.positions[:, 0], 0.8 * np.sin(t))
        assert np.allclose(states.positions[:, 1], 1.2 * np.sin(0.7 * t))
        print("vitesse max (rad/s) :", np.abs(states.velocities).max(axis=0))
        """,
        """
        t = states.times
        assert np.allclose(states.positions[:, 0], 0.8 * np.sin(t))
        assert np.allclose(states.positions[:, 1], 1.2 * np.sin(0.7 * t))
        print("top speed (rad/s):", np.abs(states.velocities).max(axis=0))
        """,
    ),
    md(
        """
        ## L'animation

        RViz redessinerait le bras à chaque message ; ici, on dessine une image par échantillon
        et on en fait un GIF. 10 images par seconde suffisent à l'œil.
        """,
        """
        ## The animation

        RViz would redraw the arm on every message; here we draw one picture per sample and make a
        GIF of them. 10 pictures a second are enough for the eye.
        """,
    ),
    code(
        """
        from bras_kit.render import render_motion, save_gif

        film = sample(motion, duration=9.0, rate=10.0)
        frames = render_motion(robot, film, size=(320, 240))
        save_gif(frames, "sinus.gif", fps=10)
        display(Image(filename="sinus.gif"))
        """
    ),
    md(
        """
        ## Les angles et leurs butées

        Une courbe se lit mieux qu'une animation pour vérifier les butées : chaque articulation, son
        angle dans le temps, et ses limites en pointillés.
        """,
        """
        ## The angles and their limits

        A plot reads better than an animation when checking limits: each joint, its angle over
        time, and its limits dashed.
        """,
    ),
    code(
        """
        from bras_kit.diagrams import plot_motion

        plot_motion(robot, states, path="angles.png")
        display(Image(filename="angles.png"))
        print("dépassements :", check_limits(robot, states))
        """,
        """
        from bras_kit.diagrams import plot_motion

        plot_motion(robot, states, path="angles.png")
        display(Image(filename="angles.png"))
        print("limit violations:", check_limits(robot, states))
        """,
    ),
    md(
        """
        ## Un mouvement par points de passage

        En production, on donne plutôt des **poses à atteindre à des instants donnés** ; le
        programme interpole entre elles. Un simple tableau CSV suffit : une colonne `time`, une
        colonne par articulation.
        """,
        """
        ## A motion through waypoints

        In production you rather give **poses to reach at given times**; the program interpolates
        between them. A plain CSV table is enough: a `time` column, one column per joint.
        """,
    ),
    code(
        """
        with open("points.csv", "w") as f:
            f.write("time,epaule,coude\\n"
                    "0,0,0\\n"
                    "2,1.0,-1.2\\n"
                    "4,-0.6,1.5\\n"
                    "6,0,0\\n")

        waypoints = waypoint_motion(robot, "points.csv", interpolation="cubic")
        print("durée :", waypoints.duration, "s")
        path_states = sample(waypoints, rate=20.0)
        print(path_states.positions[::20].round(3))
        """,
        """
        with open("points.csv", "w") as f:
            f.write("time,epaule,coude\\n"
                    "0,0,0\\n"
                    "2,1.0,-1.2\\n"
                    "4,-0.6,1.5\\n"
                    "6,0,0\\n")

        waypoints = waypoint_motion(robot, "points.csv", interpolation="cubic")
        print("duration:", waypoints.duration, "s")
        path_states = sample(waypoints, rate=20.0)
        print(path_states.positions[::20].round(3))
        """,
    ),
    md(
        """
        Avant de l'animer, vérifions-le : l'articulation `coude` doit passer de -1,2 à 1,5 rad en
        2 s. Même dans les butées de position, c'est trop rapide pour sa vitesse maximale de
        1 rad/s. `waypoint_speeds` dit quels segments et de combien :
        """,
        """
        Before animating it, check it: the `coude` joint has to go from -1.2 to 1.5 rad in 2 s.
        Even within the position limits, that is too fast for its top speed of 1 rad/s.
        `waypoint_speeds` says which segments, and by how much:
        """,
    ),
    code(
        """
        from bras_kit.motion import describe_segment, waypoint_speeds

        print(check_limits(robot, path_states))
        for segment in waypoint_speeds(robot, waypoints):
            print(bras_kit.say(describe_segment(segment)))  # a library message in the notebook's language
        """
    ),
    md(
        """
        On espace donc les points : 4,5 s pour le grand mouvement du milieu, 2,5 s pour le
        retour. Plus de dépassement ; on peut regarder.
        """,
        """
        So space the waypoints out: 4.5 s for the big move in the middle, 2.5 s for the way back.
        No more excess; now we can watch.
        """,
    ),
    code(
        """
        with open("points.csv", "w") as f:
            f.write("time,epaule,coude\\n0,0,0\\n2,1.0,-1.2\\n6.5,-0.6,1.5\\n9,0,0\\n")
        waypoints = waypoint_motion(robot, "points.csv", interpolation="cubic")
        path_states = sample(waypoints, rate=20.0)
        print(check_limits(robot, path_states))

        plot_motion(robot, path_states, path="points.png")
        display(Image(filename="points.png"))
        save_gif(render_motion(robot, sample(waypoints, rate=10.0), size=(320, 240)), "points.gif", fps=10)
        display(Image(filename="points.gif"))
        """
    ),
    md(
        """
        ## Quand le programme dépasse les butées

        Rien n'empêche d'écrire `coude = 2.5 sin t` : le message partira, et RViz affichera un
        bras qui traverse ses butées (dernière ligne du tableau des pièges). `check_limits` le
        voit avant :
        """,
        """
        ## When the program goes past the limits

        Nothing stops you writing `coude = 2.5 sin t`: the message goes out, and RViz shows an arm
        going through its end stops (the last row of the pitfalls table). `check_limits` sees it
        first:
        """,
    ),
    code(
        """
        KIND = {"position": "position", "velocity": "vitesse"}  # v.kind : le genre de butée dépassée
        wild = sample(formula_motion(robot, ["epaule=0.8*sin(t)", "coude=2.5*sin(t)"]), duration=10.0)
        for v in check_limits(robot, wild):
            print(f"{v.joint}: {KIND.get(v.kind, v.kind)} {v.value:+.3f} à t={v.peak_time:.2f} s, butée {v.bound:+.2f}, excès {v.excess:.3f}")
        """,
        """
        wild = sample(formula_motion(robot, ["epaule=0.8*sin(t)", "coude=2.5*sin(t)"]), duration=10.0)
        for v in check_limits(robot, wild):
            print(f"{v.joint}: {v.kind} {v.value:+.3f} at t={v.peak_time:.2f} s, limit {v.bound:+.2f}, excess {v.excess:.3f}")
        """,
    ),
    md(
        """
        ## Votre propre nœud, sans ROS

        Le tutoriel fait écrire le nœud lui-même : une classe `Node` de rclpy, un publisher
        `JointState` sur `joint_states`, un timer de 0,05 s qui calcule les angles et publie. Sans
        ROS installé, `bras_kit.run` exécute ce même fichier avec une **doublure** de rclpy : les
        timers se déclenchent sur une horloge simulée (10 s de nœud prennent une fraction de
        seconde), chaque message publié est enregistré, puis comparé au robot. En ligne de
        commande : `bras-kit run mon_noeud.py --urdf bras.urdf` (ou `bras-kit run PAQUET animation`).
        La vraie référence reste `ros2 run` sur une machine ROS 2.
        """,
        """
        ## Your own node, without ROS

        The tutorial has you write the node itself: an rclpy `Node` class, a `JointState` publisher
        on `joint_states`, a 0.05 s timer that computes the angles and publishes. With no ROS
        installed, `bras_kit.run` runs that very file against a **stand-in** for rclpy: timers fire
        on a simulated clock (10 s of node time take a fraction of a second), every message
        published is recorded, then compared with the robot. On the command line:
        `bras-kit run my_node.py --urdf bras.urdf` (or `bras-kit run PACKAGE animation`). The real
        thing stays `ros2 run` on a ROS 2 machine.
        """,
    ),
    code(
        """
        from bras_kit.core.i18n import say
        from bras_kit.run import joint_states, run_node
        from bras_kit.run.findings import run_findings
        from bras_kit.run.report import summary

        NODE = \'\'\'
        import math

        import rclpy
        from rclpy.node import Node
        from sensor_msgs.msg import JointState

        TOPIC = 'joint_states'
        UNIT = 1.0  # 1.0: radians


        class Oscillation(Node):
            def __init__(self):
                super().__init__('oscillation')
                self.out = self.create_publisher(JointState, TOPIC, 10)
                self.create_timer(0.05, self.step)
                self.t = 0.0

            def step(self):
                self.t += 0.05
                msg = JointState()
                msg.header.stamp = self.get_clock().now().to_msg()
                msg.name = ['epaule', 'coude']
                msg.position = [UNIT * 0.8 * math.sin(self.t), UNIT * 1.2 * math.sin(0.7 * self.t)]
                self.out.publish(msg)


        def main():
            rclpy.init()
            rclpy.spin(Oscillation())
        \'\'\'

        def try_node(source, seconds=5.0):
            with open("my_node.py", "w") as f:
                f.write(source)
            recording = run_node("my_node.py", duration=seconds)
            for line in summary(recording):
                print(say(line))
            for finding in run_findings(recording, robot):
                print(finding.code, finding.text())
            return recording


        recording = try_node(NODE)
        """
    ),
    md(
        """
        Ce que le nœud a réellement publié suit bien les deux sinusoïdes, message par message (le
        premier part au premier tic, t = 0,05 s) :
        """,
        """
        What the node really published follows the two sine waves, message by message (the first
        one leaves at the first tick, t = 0.05 s):
        """,
    ),
    code(
        """
        sent = joint_states(recording)
        assert np.allclose(sent.positions[:, 0], 0.8 * np.sin(sent.times))
        assert np.allclose(sent.positions[:, 1], 1.2 * np.sin(0.7 * sent.times))
        print(len(sent.times), sent.times[:3])
        """
    ),
    md(
        """
        Cassons-le, comme on le ferait sans le vouloir. D'abord le sujet : `joint_state` est un
        nom de sujet parfaitement valide pour ROS, mais robot_state_publisher écoute
        `/joint_states`. Le nœud tourne sans erreur… et le bras ne bouge pas :
        """,
        """
        Now break it, the way one does by accident. First the topic: `joint_state` is a perfectly
        valid topic name for ROS, but robot_state_publisher listens on `/joint_states`. The node
        runs without an error… and the arm does not move:
        """,
    ),
    code(
        """
        broken = try_node(NODE.replace("TOPIC = 'joint_states'", "TOPIC = 'joint_state'"), seconds=2.0)
        """
    ),
    md(
        """
        Ensuite l'unité : des degrés au lieu de radians. Le message part quand même (rien ne
        convertit les unités), et les positions dépassent les butées de très loin :
        """,
        """
        Then the unit: degrees instead of radians. The message still goes out (nothing converts
        units), and the positions go far past the limits:
        """,
    ),
    code(
        """
        broken = try_node(NODE.replace("UNIT = 1.0", "UNIT = 180 / math.pi"), seconds=2.0)
        """
    ),
    md(
        """
        ## À vous

        Écrivez un mouvement qui garde `epaule` fixe à 0,3 rad et fait osciller `coude` entre
        -1,5 et 1,5 rad avec une période de 4 s. Vérifiez qu'il respecte les butées (vitesses
        comprises : `velocity = 1.0` rad/s dans l'URDF !).
        """,
        """
        ## Your turn

        Write a motion that holds `epaule` at 0.3 rad and swings `coude` between -1.5 and 1.5 rad
        with a 4 s period. Check it keeps within the limits (speeds too: `velocity = 1.0` rad/s in
        the URDF!).
        """,
    ),
    code(
        """
        mine = sample(formula_motion(robot, ["epaule=0.3", "coude=1.5*sin(2*pi*t/4)"]), duration=8.0)
        print(check_limits(robot, mine))
        """
    ),
    md(
        """
        Surprise : les positions restent dans les butées, mais la **vitesse** non. La vitesse
        maximale d'une sinusoïde `A sin(2πt/T)` est `2πA/T` = 2π·1,5/4 ≈ 2,36 rad/s. Pour rester
        sous 1 rad/s avec cette amplitude, il faut une période d'au moins 2π·1,5 ≈ 9,4 s.
        """,
        """
        Surprise: the positions stay within the limits, but the **speed** does not. The top speed
        of a sine `A sin(2πt/T)` is `2πA/T` = 2π·1.5/4 ≈ 2.36 rad/s. To stay under 1 rad/s with this
        amplitude the period must be at least 2π·1.5 ≈ 9.4 s.
        """,
    ),
    code(
        """
        calm = sample(formula_motion(robot, ["epaule=0.3", "coude=1.5*sin(2*pi*t/10)"]), duration=10.0)
        print(check_limits(robot, calm))
        """
    ),
]
