"""Lesson 1: links and joints, the URDF text, changing a length."""

from ._cells import Lesson, code, md

LESSON = Lesson(
    "01",
    {"fr": "decrire-le-bras", "en": "describe-the-arm"},
    {"fr": "1 · Décrire le bras : segments et articulations", "en": "1 · Describe the arm: links and joints"},
)

LESSON.cells = [
    md(
        """
        Un bras de robot, pour ROS 2, c'est d'abord une **liste de pièces rigides** (les *segments*)
        et une **liste de charnières** entre elles (les *articulations*). Le format qui les écrit s'appelle
        URDF : du XML, lisible à l'œil.

        Dans cette leçon :

        1. lister les pièces et les charnières du bras du tutoriel ;
        2. lire l'URDF que `bras_kit` produit ;
        3. allonger le bras et voir l'articulation suivante se déplacer toute seule.
        """,
        """
        To ROS 2, a robot arm is first a **list of rigid pieces** (*links*) and a **list of hinges**
        between them (*joints*). The format that writes them down is URDF: XML you can read by eye.

        In this lesson:

        1. list the pieces and the hinges of the tutorial's arm;
        2. read the URDF that `bras_kit` produces;
        3. make the upper arm longer and watch the next joint move with it.
        """,
    ),
    code(
        """
        import difflib

        import matplotlib.pyplot as plt

        import bras_kit

        bras_kit.set_language("fr")  # messages, titres et axes de la bibliothèque en français
        robot = bras_kit.arm()  # le bras du tutoriel : base, bras, avant_bras
        """,
        """
        import difflib

        import matplotlib.pyplot as plt

        import bras_kit

        bras_kit.set_language("en")  # the library's messages, titles and axis labels in English
        robot = bras_kit.arm()  # the tutorial's arm: base, bras, avant_bras
        """,
    ),
    md(
        """
        ## Les segments : les pièces rigides

        Chaque segment a une forme visible (`visual`) : un cylindre pour la base, des pavés (`box`)
        pour le bras et l'avant-bras. L'`origin` d'une forme la place dans le repère de son segment.
        """,
        """
        ## Links: the rigid pieces

        Each link has a visible shape (`visual`): a cylinder for the base, boxes for the upper arm
        and the forearm. A shape's `origin` places it in its link's frame.
        """,
    ),
    code(
        """
        for link in robot.links:
            for visual in link.visuals:
                g = visual.geometry
                shape = f"box {g.size}" if g.kind == "box" else f"{g.kind} r={g.radius} l={g.length}"
                print(f"{link.name:11s} {shape:28s} origine {visual.origin.xyz}")
        """,
        """
        for link in robot.links:
            for visual in link.visuals:
                g = visual.geometry
                shape = f"box {g.size}" if g.kind == "box" else f"{g.kind} r={g.radius} l={g.length}"
                print(f"{link.name:11s} {shape:28s} origin {visual.origin.xyz}")
        """,
    ),
    md(
        """
        ## Les articulations : les charnières

        Une articulation relie un segment **parent** à un segment **enfant**. Trois informations comptent :

        * `origin` : où se trouve le repère de l'enfant, vu depuis le parent ;
        * `axis` : l'axe autour duquel l'enfant tourne (ici `0 1 0`, l'axe y) ;
        * `limit` : les butées, en radians.
        """,
        """
        ## Joints: the hinges

        A joint connects a **parent** link to a **child** link. Three facts matter:

        * `origin`: where the child's frame sits, seen from the parent;
        * `axis`: the axis the child turns about (here `0 1 0`, the y axis);
        * `limit`: the end stops, in radians.
        """,
    ),
    code(
        """
        for joint in robot.joints:
            lower, upper = joint.bounds()
            print(f"{joint.name:7s} {joint.type:9s} {joint.parent} -> {joint.child:10s} "
                  f"origine {joint.origin.xyz}  axe {joint.axis}  butées [{lower}, {upper}]")
        """,
        """
        for joint in robot.joints:
            lower, upper = joint.bounds()
            print(f"{joint.name:7s} {joint.type:9s} {joint.parent} -> {joint.child:10s} "
                  f"origin {joint.origin.xyz}  axis {joint.axis}  limits [{lower}, {upper}]")
        """,
    ),
    md(
        """
        ## Le texte URDF

        Voici le fichier complet, tel qu'on le donnerait à `robot_state_publisher`. Repérez
        l'`origin` de l'articulation `coude` : `z = 0.6`, exactement la longueur du bras. C'est ce qui
        accroche l'avant-bras **au bout** du bras et non à son pied.
        """,
        """
        ## The URDF text

        Here is the whole file, as you would hand it to `robot_state_publisher`. Find the
        `origin` of the `coude` joint: `z = 0.6`, exactly the length of the upper arm. That is
        what hangs the forearm **at the tip** of the upper arm rather than at its foot.
        """,
    ),
    code(
        """
        urdf = bras_kit.arm_urdf()
        print(urdf)
        """
    ),
    md(
        """
        ## Changer une longueur

        Le bras est fabriqué à partir d'un modèle paramétré (un fichier *xacro*, voir la leçon 10).
        Chaque nombre est un paramètre. Allongeons le bras à 0,8 m :
        """,
        """
        ## Change a length

        The arm is made from a parameterised template (a *xacro* file, see lesson 10). Every
        number is a parameter. Let us make the upper arm 0.8 m long:
        """,
    ),
    code(
        """
        longer = bras_kit.arm(params={"bras_length": 0.8})
        print("origine du coude :", robot.joint("coude").origin.xyz, "->", longer.joint("coude").origin.xyz)
        bras_visual = longer.link("bras").visuals[0]
        print("forme du bras :", bras_visual.geometry.size, "centrée en", bras_visual.origin.xyz)
        """,
        """
        longer = bras_kit.arm(params={"bras_length": 0.8})
        print("coude origin:", robot.joint("coude").origin.xyz, "->", longer.joint("coude").origin.xyz)
        bras_visual = longer.link("bras").visuals[0]
        print("upper-arm shape:", bras_visual.geometry.size, "centred at", bras_visual.origin.xyz)
        """,
    ),
    md(
        """
        Trois nombres ont changé d'un coup : la hauteur de la boîte, le centre de la boîte (la
        moitié de la longueur) et l'origine du coude. Le `diff` des deux URDF le montre :
        """,
        """
        Three numbers changed at once: the box's height, the box's centre (half the length) and the
        elbow's origin. A `diff` of the two URDFs shows it:
        """,
    ),
    code(
        """
        before = urdf.splitlines()
        after = bras_kit.arm_urdf(params={"bras_length": 0.8}).splitlines()
        for line in difflib.unified_diff(before, after, "bras.urdf", "bras-0.8.urdf", n=0, lineterm=""):
            print(line)
        """
    ),
    md(
        """
        Et en image (le rendu est expliqué à la leçon 3). Pour comparer deux longueurs, les deux images
        doivent avoir le même cadrage : chacune est posée sur les mêmes axes, en mètres.
        """,
        """
        And as a picture (rendering is explained in lesson 3). To compare two lengths, both pictures
        need the same framing: each one is placed on the same axes, in metres.
        """,
    ),
    code(
        """
        import math

        from bras_kit.render import Renderer


        def front_view(ax, arm, pose, distance=3.0):
            \"""Le bras vu de face, posé sur des axes en mètres : ceux du plan y = 0 où il bouge.\"""
            with Renderer(arm, fit=pose, view="front", distance=distance, size=(400, 400)) as renderer:
                picture = renderer.render(pose)
                camera = renderer.camera
            x, y, z = camera.pose[:3, 3]  # la caméra est du côté y < 0, à -y mètres du plan y = 0
            half = -y * math.tan(camera.yfov / 2)  # la moitié de ce qu'elle voit de ce plan, en mètres
            ax.imshow(picture, extent=(x - half, x + half, z - half, z + half))


        # mêmes axes pour les deux images : un seul cadrage, les longueurs se comparent à l'œil
        fig, axes = plt.subplots(1, 2, figsize=(8, 4.5), sharex=True, sharey=True)
        for ax, (label, arm) in zip(axes, [("bras_length = 0.6", robot), ("bras_length = 0.8", longer)]):
            front_view(ax, arm, {"coude": 0.6})
            ax.set_title(label)
            ax.set_xlabel("x (m)")
        axes[0].set_ylabel("z (m)")
        axes[0].set_xlim(-0.5, 0.8)
        axes[0].set_ylim(-0.15, 1.45)
        plt.show()
        """,
        """
        import math

        from bras_kit.render import Renderer


        def front_view(ax, arm, pose, distance=3.0):
            \"""The arm seen from the front, placed on axes in metres: those of the plane y = 0 it moves in.\"""
            with Renderer(arm, fit=pose, view="front", distance=distance, size=(400, 400)) as renderer:
                picture = renderer.render(pose)
                camera = renderer.camera
            x, y, z = camera.pose[:3, 3]  # the camera is on the y < 0 side, -y metres from the plane y = 0
            half = -y * math.tan(camera.yfov / 2)  # half of what it sees of that plane, in metres
            ax.imshow(picture, extent=(x - half, x + half, z - half, z + half))


        # the same axes for both pictures: one framing, so the lengths compare by eye
        fig, axes = plt.subplots(1, 2, figsize=(8, 4.5), sharex=True, sharey=True)
        for ax, (label, arm) in zip(axes, [("bras_length = 0.6", robot), ("bras_length = 0.8", longer)]):
            front_view(ax, arm, {"coude": 0.6})
            ax.set_title(label)
            ax.set_xlabel("x (m)")
        axes[0].set_ylabel("z (m)")
        axes[0].set_xlim(-0.5, 0.8)
        axes[0].set_ylim(-0.15, 1.45)
        plt.show()
        """,
    ),
    md(
        """
        ## À vous

        Les paramètres du modèle sont listés par `bras_kit.template_parameters()`. Raccourcissez
        l'avant-bras à 0,3 m et vérifiez quelle valeur change dans l'URDF. (L'articulation `coude` ne
        bouge pas : pourquoi ?)
        """,
        """
        ## Your turn

        The template's parameters are listed by `bras_kit.template_parameters()`. Make the forearm
        0.3 m long and check which value changes in the URDF. (The `coude` joint does not move:
        why?)
        """,
    ),
    code(
        """
        KINDS = {"flag": "oui/non", "number": "nombre", "colour": "couleur"}
        for p in bras_kit.template_parameters().values():
            print(f"{p.name:18s} {KINDS.get(p.kind, p.kind):8s} {p.default}")
        """,
        """
        for p in bras_kit.template_parameters().values():
            print(f"{p.name:18s} {p.kind:7s} {p.default}")
        """,
    ),
    code(
        """
        short = bras_kit.arm(params={"avant_bras_length": 0.3})
        print(short.link("avant_bras").visuals[0].geometry.size, short.joint("coude").origin.xyz)
        """
    ),
]
