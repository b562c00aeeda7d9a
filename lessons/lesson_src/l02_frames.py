"""Lesson 2: the frame tree, forward kinematics by hand, then with bras_kit."""

from ._cells import Lesson, code, md

LESSON = Lesson(
    "02",
    {"fr": "arbre-des-reperes", "en": "frame-tree"},
    {"fr": "2 · L'arbre des repères", "en": "2 · The frame tree"},
)

LESSON.cells = [
    md(
        """
        Chaque segment porte son propre **repère** (une origine et trois axes). Les repères
        s'emboîtent : celui du bras est défini par rapport à la base, celui de l'avant-bras par
        rapport au bras. C'est l'arbre que `robot_state_publisher` publie sur TF.

        Question de la leçon : pour `epaule = 0.5` et `coude = -0.8`, **où est le repère
        `avant_bras`** dans le repère `base` ? On le calcule à la main, puis on vérifie.
        """,
        """
        Every link carries its own **frame** (an origin and three axes). Frames nest: the upper
        arm's is given relative to the base, the forearm's relative to the upper arm. That is the
        tree `robot_state_publisher` publishes on TF.

        The question of this lesson: with `epaule = 0.5` and `coude = -0.8`, **where is the
        `avant_bras` frame** in the `base` frame? We work it out by hand, then check.
        """,
    ),
    code(
        """
        import numpy as np

        import bras_kit

        bras_kit.set_language("@LANG@")  # the library's messages and picture words in this notebook's language
        robot = bras_kit.arm()
        pose = {"epaule": 0.5, "coude": -0.8}
        np.set_printoptions(precision=4, suppress=True)
        """
    ),
    md(
        r"""
        ## À la main

        Une transformation se note avec une matrice 4×4 : rotation en haut à gauche, translation
        dans la dernière colonne. Une articulation `revolute` fait deux choses, dans cet ordre :

        1. se décaler de son `origin` (une translation) ;
        2. tourner de l'angle de l'articulation autour de son `axis` (ici y).

        Une rotation d'angle $\theta$ autour de y :
        $R_y(\theta) = \begin{pmatrix} \cos\theta & 0 & \sin\theta \\ 0 & 1 & 0 \\ -\sin\theta & 0 & \cos\theta \end{pmatrix}$
        """,
        r"""
        ## By hand

        A transform is written as a 4×4 matrix: rotation top left, translation in the last
        column. A `revolute` joint does two things, in this order:

        1. shift by its `origin` (a translation);
        2. turn by the joint's angle about its `axis` (here y).

        A rotation by $\theta$ about y:
        $R_y(\theta) = \begin{pmatrix} \cos\theta & 0 & \sin\theta \\ 0 & 1 & 0 \\ -\sin\theta & 0 & \cos\theta \end{pmatrix}$
        """,
    ),
    code(
        """
        def translation(x, y, z):
            m = np.eye(4)
            m[:3, 3] = (x, y, z)
            return m


        def rotation_y(angle):
            c, s = np.cos(angle), np.sin(angle)
            m = np.eye(4)
            m[:3, :3] = [[c, 0, s], [0, 1, 0], [-s, 0, c]]
            return m


        base_to_bras = translation(0, 0, 0.05) @ rotation_y(pose["epaule"])      # joint epaule
        bras_to_avant_bras = translation(0, 0, 0.6) @ rotation_y(pose["coude"])  # joint coude
        by_hand = base_to_bras @ bras_to_avant_bras
        print(by_hand)
        """
    ),
    md(
        """
        Lisons la dernière colonne : le coude est à `x = 0.6·sin(0.5) ≈ 0.288` et
        `z = 0.05 + 0.6·cos(0.5) ≈ 0.577`. Le bloc de rotation est une rotation autour de y de
        `0.5 + (-0.8) = -0.3` rad : deux rotations autour du même axe s'additionnent.
        """,
        """
        Read the last column: the elbow is at `x = 0.6·sin(0.5) ≈ 0.288` and
        `z = 0.05 + 0.6·cos(0.5) ≈ 0.577`. The rotation block is a turn about y by
        `0.5 + (-0.8) = -0.3` rad: two turns about the same axis add up.
        """,
    ),
    code(
        """
        print("x =", 0.6 * np.sin(0.5), " z =", 0.05 + 0.6 * np.cos(0.5))
        print(np.allclose(by_hand, translation(0.6 * np.sin(0.5), 0, 0.05 + 0.6 * np.cos(0.5)) @ rotation_y(-0.3)))
        """
    ),
    md(
        """
        ## La même chose avec bras_kit

        `bras_kit.tf_tree` compile l'arbre une fois ; `bras_kit.fk` (cinématique directe, *forward
        kinematics*) donne la pose de chaque segment dans le repère racine.
        """,
        """
        ## The same with bras_kit

        `bras_kit.tf_tree` compiles the tree once; `bras_kit.fk` (forward kinematics) gives every
        link's pose in the root frame.
        """,
    ),
    code(
        """
        tree = bras_kit.tf_tree(robot)
        print("segments      :", tree.links)
        print("parents       :", [tree.links[p] if p >= 0 else None for p in tree.parent])
        print("articulations :", tree.dof)

        poses = bras_kit.fk(tree, pose)
        print(poses["avant_bras"])
        assert np.allclose(poses["avant_bras"], by_hand)
        """,
        """
        tree = bras_kit.tf_tree(robot)
        print("links  :", tree.links)
        print("parents:", [tree.links[p] if p >= 0 else None for p in tree.parent])
        print("joints :", tree.dof)

        poses = bras_kit.fk(tree, pose)
        print(poses["avant_bras"])
        assert np.allclose(poses["avant_bras"], by_hand)
        """,
    ),
    md(
        """
        Le bout de l'outil n'a pas de repère à lui : c'est le point `z = 0.5` (la longueur de
        l'avant-bras) dans le repère `avant_bras`. On l'y amène avec la même matrice :
        """,
        """
        The tool tip has no frame of its own: it is the point `z = 0.5` (the forearm's length) in
        the `avant_bras` frame. The same matrix carries it over:
        """,
    ),
    code(
        """
        tip = poses["avant_bras"] @ [0, 0, 0.5, 1]
        print("bout de l'outil :", tip[:3])
        """,
        """
        tip = poses["avant_bras"] @ [0, 0, 0.5, 1]
        print("tool tip:", tip[:3])
        """,
    ),
    md(
        """
        ## Ce que `tf2_echo` afficherait

        `ros2 run tf2_ros tf2_echo bras avant_bras` donne la pose d'un repère dans un autre, en
        translation + quaternion. `relative_transform` calcule la même chose :
        """,
        """
        ## What `tf2_echo` would print

        `ros2 run tf2_ros tf2_echo bras avant_bras` gives one frame's pose in another, as a
        translation and a quaternion. `relative_transform` computes the same thing:
        """,
    ),
    code(
        """
        from bras_kit.kinematics import describe_transform

        echo = describe_transform(bras_kit.relative_transform(tree, pose, "bras", "avant_bras"))
        for key, values in echo.items():
            print(f"{key:9s}", np.round(values, 6) + 0.0)  # + 0.0 turns -0.0 into 0.0
        """
    ),
    md(
        """
        ## Le schéma de l'arbre

        `ros2 run tf2_tools view_frames` dessine l'arbre des repères. `bras_kit` dessine le même
        schéma sans ROS :
        """,
        """
        ## The tree diagram

        `ros2 run tf2_tools view_frames` draws the frame tree. `bras_kit` draws the same diagram
        without ROS:
        """,
    ),
    code(
        """
        from IPython.display import Image, display

        from bras_kit.diagrams import frame_diagram

        frame_diagram(robot, config=pose, path="frames.png")
        display(Image("frames.png"))
        """
    ),
    md(
        """
        ## À vous

        Pour quelle valeur de `coude` l'avant-bras est-il horizontal quand `epaule = 0.5` ?
        (Indice : les angles s'additionnent ; horizontal veut dire `±π/2` depuis la verticale.)
        Vérifiez avec `fk` : la composante z du bout doit égaler celle du coude.
        """,
        """
        ## Your turn

        For which `coude` value is the forearm horizontal when `epaule = 0.5`? (Hint: the angles
        add up; horizontal means `±π/2` from vertical.) Check with `fk`: the tip's z must equal
        the elbow's.
        """,
    ),
    code(
        """
        coude = np.pi / 2 - 0.5
        check = bras_kit.fk(tree, {"epaule": 0.5, "coude": coude})
        print(check["avant_bras"][2, 3], (check["avant_bras"] @ [0, 0, 0.5, 1])[2])
        """
    ),
]
