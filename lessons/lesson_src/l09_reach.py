"""Lesson 9: inverse kinematics of the two-joint arm: both elbows, unreachable targets."""

from ._cells import Lesson, code, md

LESSON = Lesson(
    "09",
    {"fr": "atteindre-un-point", "en": "reaching-a-point"},
    {"fr": "9 · Atteindre un point : la cinématique inverse", "en": "9 · Reaching a point: inverse kinematics"},
)

LESSON.cells = [
    md(
        """
        Jusqu'ici, on donnait des angles et on calculait où allait le bout (cinématique
        **directe**, leçon 2). Le problème utile est l'inverse : **« mets le bout de l'outil
        ici »**. Quels angles faut-il ? C'est la cinématique **inverse**. Pour notre bras à deux
        articulations parallèles, c'est un triangle, et il a en général **deux** solutions : coude d'un
        côté ou de l'autre.
        """,
        """
        So far we gave angles and worked out where the tip went (**forward** kinematics, lesson 2).
        The useful problem is the reverse: **"put the tool tip here"**. Which angles does it take?
        That is **inverse** kinematics. For our arm with two parallel joints it is a triangle, and
        there are usually **two** answers: the elbow on one side or the other.
        """,
    ),
    code(
        """
        import matplotlib.pyplot as plt
        import numpy as np

        import bras_kit
        from bras_kit.ik import ik_2r

        bras_kit.set_language("fr")  # messages, titres et axes de la bibliothèque en français
        robot = bras_kit.arm()
        tree = bras_kit.tf_tree(robot)
        L1, L2, H = 0.6, 0.5, 0.05  # bras, avant-bras, hauteur de l'épaule
        target = np.array([0.6, 0.0, 0.7])
        """,
        """
        import matplotlib.pyplot as plt
        import numpy as np

        import bras_kit
        from bras_kit.ik import ik_2r

        bras_kit.set_language("en")  # the library's messages, titles and axis labels in English
        robot = bras_kit.arm()
        tree = bras_kit.tf_tree(robot)
        L1, L2, H = 0.6, 0.5, 0.05  # upper arm, forearm, shoulder height
        target = np.array([0.6, 0.0, 0.7])
        """,
    ),
    md(
        r"""
        ## À la main : le triangle

        Le bras bouge dans le plan x-z. Depuis l'épaule, la cible est à la distance $d$. Les
        côtés du triangle épaule–coude–bout sont $L_1$, $L_2$ et $d$ ; la loi des cosinus donne
        l'angle du coude :
        $\cos(\text{coude}) = \dfrac{d^2 - L_1^2 - L_2^2}{2 L_1 L_2}$, deux signes possibles.
        L'épaule vise la cible, corrigée de l'angle que fait l'avant-bras :
        $\text{epaule} = \operatorname{atan2}(x, z - H) - \operatorname{atan2}(L_2 \sin \text{coude}, L_1 + L_2 \cos \text{coude})$.
        """,
        r"""
        ## By hand: the triangle

        The arm moves in the x-z plane. Seen from the shoulder, the target is at distance $d$. The
        sides of the shoulder–elbow–tip triangle are $L_1$, $L_2$ and $d$; the law of cosines gives
        the elbow angle:
        $\cos(\text{coude}) = \dfrac{d^2 - L_1^2 - L_2^2}{2 L_1 L_2}$, with two possible signs.
        The shoulder aims at the target, corrected by the angle the forearm makes:
        $\text{epaule} = \operatorname{atan2}(x, z - H) - \operatorname{atan2}(L_2 \sin \text{coude}, L_1 + L_2 \cos \text{coude})$.
        """,
    ),
    code(
        """
        def by_hand(x, z, sign=+1):
            d2 = x**2 + (z - H) ** 2
            coude = sign * np.arccos((d2 - L1**2 - L2**2) / (2 * L1 * L2))
            epaule = np.arctan2(x, z - H) - np.arctan2(L2 * np.sin(coude), L1 + L2 * np.cos(coude))
            return {"epaule": float(epaule), "coude": float(coude)}


        def tip(pose):
            return (bras_kit.fk(tree, pose)["avant_bras"] @ [0, 0, L2, 1])[:3]


        for sign in (+1, -1):
            pose = by_hand(target[0], target[2], sign)
            print(pose, "->", tip(pose).round(6))
        """
    ),
    md(
        """
        Les deux poses mettent le bout exactement sur la cible. `ik_2r` fait le même calcul, mais
        lit les longueurs dans le modèle (changez `bras_length` : il suit) et vérifie les
        butées :
        """,
        """
        Both poses put the tip exactly on the target. `ik_2r` does the same sum, but reads the
        lengths from the model (change `bras_length`: it follows) and checks the limits:
        """,
    ),
    code(
        """
        COUDE = {"up": "haut", "down": "bas"}  # solution.elbow : "up" ou "down"
        result = ik_2r(robot, target)
        print(result.reachable, "-", bras_kit.say(result.message))
        for solution in result.solutions:
            print(f"  coude {COUDE[solution.elbow]:4s}: {solution.joints}  dans les butées : {solution.within_limits}")
        print("choisie :", result.joints, " écart :", result.residual)
        """,
        """
        result = ik_2r(robot, target)
        print(result.reachable, "-", bras_kit.say(result.message))
        for solution in result.solutions:
            print(f"  elbow {solution.elbow:4s}: {solution.joints}  within limits: {solution.within_limits}")
        print("chosen:", result.joints, " error:", result.residual)
        """,
    ),
    md(
        """
        ## Les deux coudes en image

        Un dessin en bâtons (repères `base`, `bras`, `avant_bras` et le bout) vu de face, dans le
        plan x-z :
        """,
        """
        ## Both elbows as a picture

        A stick drawing (frames `base`, `bras`, `avant_bras` and the tip) seen from the front, in
        the x-z plane:
        """,
    ),
    code(
        """
        def stick(ax, pose, **style):
            poses = bras_kit.fk(tree, pose)
            points = [poses["bras"][:3, 3], poses["avant_bras"][:3, 3], tip(pose)]
            xs, zs = zip(*[(p[0], p[2]) for p in [(0, 0, 0), *points]])
            ax.plot(xs, zs, "o-", lw=4, **style)


        fig, ax = plt.subplots(figsize=(5, 5))
        for solution, colour in zip(result.solutions, ("tab:blue", "tab:orange")):
            stick(ax, solution.joints, color=colour, label=f"coude {COUDE[solution.elbow]}")
        ax.plot(target[0], target[2], "k*", ms=15, label="cible")
        ax.add_patch(plt.Circle((0, H), L1 + L2, fill=False, ls=":", color="grey"))
        ax.set_aspect("equal")
        ax.set_xlim(-1.2, 1.2)
        ax.set_ylim(-0.6, 1.3)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("z (m)")
        ax.legend(loc="upper left")
        plt.show()
        """,
        """
        def stick(ax, pose, **style):
            poses = bras_kit.fk(tree, pose)
            points = [poses["bras"][:3, 3], poses["avant_bras"][:3, 3], tip(pose)]
            xs, zs = zip(*[(p[0], p[2]) for p in [(0, 0, 0), *points]])
            ax.plot(xs, zs, "o-", lw=4, **style)


        fig, ax = plt.subplots(figsize=(5, 5))
        for solution, colour in zip(result.solutions, ("tab:blue", "tab:orange")):
            stick(ax, solution.joints, color=colour, label=f"elbow {solution.elbow}")
        ax.plot(target[0], target[2], "k*", ms=15, label="target")
        ax.add_patch(plt.Circle((0, H), L1 + L2, fill=False, ls=":", color="grey"))
        ax.set_aspect("equal")
        ax.set_xlim(-1.2, 1.2)
        ax.set_ylim(-0.6, 1.3)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("z (m)")
        ax.legend(loc="upper left")
        plt.show()
        """,
    ),
    md(
        """
        ## Quand la cible est hors d'atteinte

        Trois façons d'échouer, et un message pour chacune :

        * trop loin : plus loin que `L1 + L2 = 1.1` m de l'épaule ;
        * hors du plan : le bras ne tourne qu'autour de y, il ne peut pas sortir du plan `y = 0` ;
        * derrière les butées : le triangle existe, mais une articulation devrait dépasser ses limites.

        Dans chaque cas, `result.joints` donne la pose la plus proche **dans les butées**.
        """,
        """
        ## When the target is out of reach

        Three ways to fail, and a message for each:

        * too far: more than `L1 + L2 = 1.1` m from the shoulder;
        * off the plane: the arm only turns about y, it cannot leave the `y = 0` plane;
        * past the limits: the triangle exists, but a joint would have to go past its limits.

        In every case `result.joints` gives the closest pose **within the limits**.
        """,
    ),
    code(
        """
        for point in ([1.5, 0, 0.5], [0.4, 0.3, 0.5], [0.2, 0, -0.2]):
            failed = ik_2r(robot, point)
            print(point, failed.reachable, failed.reason)
            print("   ", bras_kit.say(failed.message))
        """
    ),
    md(
        """
        ## Y aller

        Une solution n'est qu'une pose d'arrivée. Pour y **aller**, `reach_motion` fabrique un
        mouvement doux (vitesse nulle au départ et à l'arrivée), assez lent pour les limites de
        vitesse des articulations :
        """,
        """
        ## Getting there

        A solution is only an end pose. To **get there**, `reach_motion` builds a smooth move (zero
        speed at start and end), slow enough for the joints' velocity limits:
        """,
    ),
    code(
        """
        from IPython.display import Image, display

        from bras_kit.ik import reach_motion
        from bras_kit.render import render_motion, save_gif

        move = reach_motion(robot, {}, result.joints)
        print(f"durée : {move.duration:.2f} s, vitesses de pointe : {move.peak_velocities().round(3)}")
        poses = move.positions(move.times(rate=10.0))  # une ligne par image, colonnes epaule, coude
        save_gif(render_motion(robot, poses, size=(320, 240)), "atteindre.gif", fps=10)
        display(Image(filename="atteindre.gif"))
        """,
        """
        from IPython.display import Image, display

        from bras_kit.ik import reach_motion
        from bras_kit.render import render_motion, save_gif

        move = reach_motion(robot, {}, result.joints)
        print(f"duration: {move.duration:.2f} s, peak speeds: {move.peak_velocities().round(3)}")
        poses = move.positions(move.times(rate=10.0))  # one row per picture, columns epaule, coude
        save_gif(render_motion(robot, poses, size=(320, 240)), "reach.gif", fps=10)
        display(Image(filename="reach.gif"))
        """,
    ),
    md(
        """
        ## À vous

        1. Trouvez une cible que **seul** le coude « bas » (`down`) atteint dans les butées.
        2. Avec le poignet (`bras_kit.arm(wrist=True)`), il y a trois articulations pour deux
           coordonnées : une infinité de solutions. `bras_kit.solve_ik` cherche alors
           numériquement. Essayez-le sur la même cible.
        """,
        """
        ## Your turn

        1. Find a target that **only** the "down" elbow reaches within the limits.
        2. With the wrist (`bras_kit.arm(wrist=True)`) there are three joints for two coordinates:
           endless solutions. `bras_kit.solve_ik` then searches numerically. Try it on the same
           target.
        """,
    ),
    code(
        """
        wrist_arm = bras_kit.arm(wrist=True)
        numeric = bras_kit.solve_ik(wrist_arm, target)
        print(numeric.method, numeric.reachable, {k: round(v, 3) for k, v in numeric.joints.items()}, numeric.residual)
        """
    ),
]
