"""Lesson 11: physics with MuJoCo — drop the arm, hold it, track the sine, a weak motor, gravity compensation."""

from ._cells import Lesson, code, md

LESSON = Lesson(
    "11",
    {"fr": "physique", "en": "physics"},
    {"fr": "11 · Physique : pourquoi le bras ne tombe pas dans RViz",
     "en": "11 · Physics: why the arm does not fall in RViz"},
)

LESSON.cells = [
    md(
        """
        Dans RViz, on peut mettre l'épaule à l'horizontale et laisser le bras ainsi pendant des
        heures : rien ne plie. RViz ne fait que **dessiner** chaque segment là où `/joint_states`
        l'indique ; il ne se demande jamais si un moteur pourrait tenir cette pose. Pour le
        savoir, il faut un moteur physique. bras-kit utilise **MuJoCo** : la pesanteur agit sur
        les masses des balises `<inertial>`, chaque moteur pousse au plus de `<limit effort>`, et
        les formes `<collision>` rencontrent le sol.

        Premier essai avec le bras du tutoriel tel quel, sans masses :
        """,
        """
        In RViz you can put the shoulder level and leave the arm there for hours: nothing bends.
        RViz only **draws** each link where `/joint_states` puts it; it never asks whether a motor
        could hold that pose. To find out you need a physics engine. bras-kit uses **MuJoCo**:
        gravity acts on the masses of the `<inertial>` elements, each motor pushes with at most
        `<limit effort>`, and the `<collision>` shapes meet the floor.

        A first try with the tutorial's arm as it is, without masses:
        """,
    ),
    code(
        """
        import numpy as np

        import bras_kit
        from bras_kit.core.i18n import say_error
        from bras_kit.physics.diagnostics import report_text

        bras_kit.set_language("@LANG@")  # the library's messages and picture words in this notebook's language
        try:
            bras_kit.simulate(bras_kit.arm(), lang="@LANG@")
        except bras_kit.ModelError as error:
            print(say_error(error))  # the error's words, in the library's language
        """
    ),
    md(
        """
        Un corps sans masse ne peut pas être simulé : c'est l'exercice 7 (les inerties) qui rend
        la physique possible. Avec `inertials=True`, chaque segment reçoit masse et inertie, et aussi
        une forme de collision identique à sa forme visible.

        ## 1. Lâcher le bras

        Moteurs coupés (`control="none"`). Droit vers le haut, le bras est en équilibre instable :
        on le penche de 0,05 rad pour qu'il tombe.
        """,
        """
        A body with no mass cannot be simulated: exercise 7 (inertials) is what makes physics
        possible. With `inertials=True` every link gets a mass and an inertia, and a collision
        shape equal to its visible shape.

        ## 1. Drop the arm

        Motors off (`control="none"`). Straight up, the arm is balanced on a knife edge: we tilt it
        by 0.05 rad so that it falls.
        """,
    ),
    code(
        """
        robot = bras_kit.arm(inertials=True)
        fall = bras_kit.simulate(robot, control="none", start={"epaule": 0.05, "coude": 0.05}, duration=4)
        print(report_text(robot, fall, "@LANG@"))
        """
    ),
    code(
        """
        bras_kit.show_gif(bras_kit.render_motion(robot, fall, size=(320, 240)), fps=20)
        """
    ),
    md(
        """
        Le coude se plie jusqu'à sa butée et l'avant-bras se pose sur le sol : sans moteur, rien ne
        tient la pose que RViz affichait.

        ## 2. Tenir le bras

        Allumons les moteurs. Chacun est un asservissement PD :
        couple = kp · (consigne − q) + kd · (vitesse de consigne − vitesse), limité à ±effort.
        Demandons une pose fixe, épaule 0,5 rad, coude 0,3 rad.
        """,
        """
        The elbow folds onto its stop and the forearm lands on the floor: with no motor, nothing
        holds the pose RViz was showing.

        ## 2. Hold the arm

        Switch the motors on. Each is a PD servo:
        torque = kp · (target − q) + kd · (target speed − speed), clipped to ±effort.
        Ask for a fixed pose, shoulder 0.5 rad, elbow 0.3 rad.
        """,
    ),
    code(
        """
        pose = {"epaule": 0.5, "coude": 0.3}
        hold = bras_kit.simulate(robot, bras_kit.pose_motion(robot, pose), control="pd", duration=3)
        error = np.array(list(pose.values())) - hold.positions[-1]
        print("écart (rad)   :", error.round(4))
        print("couple (N.m) :", hold.efforts[-1].round(3))
        """,
        """
        pose = {"epaule": 0.5, "coude": 0.3}
        hold = bras_kit.simulate(robot, bras_kit.pose_motion(robot, pose), control="pd", duration=3)
        error = np.array(list(pose.values())) - hold.positions[-1]
        print("error (rad):", error.round(4))
        print("torque (N.m):", hold.efforts[-1].round(3))
        """,
    ),
    md(
        """
        Le bras tient, mais un peu plus bas que demandé. Un ressort ne pousse que s'il est étiré :
        le moteur PD doit **s'écarter** de la consigne pour produire le couple qui compense le
        poids. Vérifions à la main le couple de pesanteur : pour chaque segment au-delà de l'articulation,
        masse × g × bras de levier horizontal (bras : 1 kg, centre à 0,3 m ; avant-bras : 0,5 kg,
        centre à 0,25 m du coude, coude à 0,6 m).
        """,
        """
        The arm holds, but a little lower than asked. A spring only pushes when stretched: the PD
        motor must **drift away** from its target to produce the torque that carries the weight.
        Let's check the gravity torque by hand: for each link beyond the joint, mass × g ×
        horizontal lever arm (upper arm: 1 kg, centre at 0.3 m; forearm: 0.5 kg, centre 0.25 m past
        the elbow, elbow at 0.6 m).
        """,
    ),
    code(
        """
        g = 9.81
        q1, q2 = hold.positions[-1]
        shoulder = g * (1.0 * 0.3 * np.sin(q1) + 0.5 * (0.6 * np.sin(q1) + 0.25 * np.sin(q1 + q2)))
        elbow = g * 0.5 * 0.25 * np.sin(q1 + q2)
        print("à la main :", np.round([-shoulder, -elbow], 3))
        print("kp × écart :", np.round(100 * error, 3))
        """,
        """
        g = 9.81
        q1, q2 = hold.positions[-1]
        shoulder = g * (1.0 * 0.3 * np.sin(q1) + 0.5 * (0.6 * np.sin(q1) + 0.25 * np.sin(q1 + q2)))
        elbow = g * 0.5 * 0.25 * np.sin(q1 + q2)
        print("by hand   :", np.round([-shoulder, -elbow], 3))
        print("kp x error:", np.round(100 * error, 3))
        """,
    ),
    md(
        """
        ## 3. Suivre la sinusoïde

        Le mouvement par défaut est celui du nœud du tutoriel (`epaule = 0,8 sin t`,
        `coude = 1,2 sin 0,7t`). Le rapport donne, par articulation, l'erreur de suivi, le couple maximal,
        la part du temps passée à la limite d'effort, et le couple que le mouvement exige vraiment
        (dynamique inverse le long de la consigne).
        """,
        """
        ## 3. Track the sine

        The default motion is the tutorial node's (`epaule = 0.8 sin t`, `coude = 1.2 sin 0.7t`).
        The report gives, per joint, the tracking error, the peak torque, the share of time spent
        at the effort limit, and the torque the motion really needs (inverse dynamics along the
        reference).
        """,
    ),
    code(
        """
        from bras_kit.physics.plot import save_torque_plot

        track = bras_kit.simulate(robot, control="pd")
        print(report_text(robot, track, "@LANG@"))
        save_torque_plot(robot, track, "track.png", "@LANG@")
        bras_kit.show_image("track.png")
        """
    ),
    md(
        """
        ## 4. Un moteur trop faible

        Dans l'URDF, `effort` n'est pas décoratif. Donnons 2 N·m à l'épaule au lieu de 10 :
        """,
        """
        ## 4. A motor too weak

        In the URDF, `effort` is not decoration. Give the shoulder 2 N·m instead of 10:
        """,
    ),
    code(
        """
        weak_robot = bras_kit.arm(inertials=True, params={"epaule_effort": 2})
        weak = bras_kit.simulate(weak_robot, control="pd")
        print(report_text(weak_robot, weak, "@LANG@"))
        save_torque_plot(weak_robot, weak, "weak.png", "@LANG@")
        bras_kit.show_image("weak.png")
        """
    ),
    md(
        """
        Le couple reste collé à la bande rouge : le moteur donne tout ce qu'il a et le bras tombe
        malgré tout. RViz aurait montré la sinusoïde parfaite.

        ## 5. Compenser la pesanteur

        Un vrai contrôleur ajoute à la commande PD le couple qui annule la pesanteur, calculé avec
        le modèle (c'est `pd+gravity`). Le PD n'a plus qu'à corriger les petits écarts :
        """,
        """
        The torque sticks to the red band: the motor gives all it has and the arm drops anyway.
        RViz would have shown a perfect sine.

        ## 5. Cancel gravity

        A real controller adds to the PD command the torque that cancels gravity, computed from the
        model (that is `pd+gravity`). The PD part only has small errors left to correct:
        """,
    ),
    code(
        """
        compensated = bras_kit.simulate(robot, control="pd+gravity")
        for plain, better in zip(track.report, compensated.report):
            print(f"{plain.joint:8s} écart moyen : pd {plain.error_mean:.4f} rad, pd+gravity {better.error_mean:.4f} rad")
        """,
        """
        compensated = bras_kit.simulate(robot, control="pd+gravity")
        for plain, better in zip(track.report, compensated.report):
            print(f"{plain.joint:8s} mean error: pd {plain.error_mean:.4f} rad, pd+gravity {better.error_mean:.4f} rad")
        """,
    ),
    md(
        """
        ## Pourquoi le bras ne tombe pas dans RViz

        `joint_state_publisher` et le nœud du tutoriel **écrivent** les angles ; personne ne les
        calcule à partir de forces. C'est comme si chaque articulation avait un moteur infiniment
        puissant avec une compensation de pesanteur parfaite. Pour voir ce que ferait le vrai bras,
        il faut les masses (`<inertial>`), les limites d'effort et un moteur physique : Gazebo dans
        le monde ROS, MuJoCo ici. `bras-kit mjcf --inertials -o bras.xml` écrit le modèle pour le
        visualiseur de MuJoCo.

        **À vous :** trouvez le plus petit `epaule_effort` pour lequel le rapport ne dit plus
        « trop faible », avec `pd` puis avec `pd+gravity`. Pourquoi est-ce le même ?
        """,
        """
        ## Why the arm does not fall in RViz

        `joint_state_publisher` and the tutorial's node **write** the angles; nobody works them out
        from forces. It is as if every joint had an infinitely strong motor with perfect gravity
        compensation. To see what the real arm would do you need the masses (`<inertial>`), the
        effort limits and a physics engine: Gazebo in the ROS world, MuJoCo here.
        `bras-kit mjcf --inertials -o bras.xml` writes the model for MuJoCo's viewer.

        **Your turn:** find the smallest `epaule_effort` for which the report no longer says "too
        weak", with `pd` then with `pd+gravity`. Why is it the same?
        """,
    ),
    code(
        """
        for effort in (4, 5, 6, 7):
            candidate = bras_kit.arm(inertials=True, params={"epaule_effort": effort})
            result = bras_kit.simulate(candidate, control="pd+gravity", duration=10)
            print(effort, "N.m ->", "trop faible" if result.weak_joints else "ok")
        """,
        """
        for effort in (4, 5, 6, 7):
            candidate = bras_kit.arm(inertials=True, params={"epaule_effort": effort})
            result = bras_kit.simulate(candidate, control="pd+gravity", duration=10)
            print(effort, "N.m ->", "too weak" if result.weak_joints else "ok")
        """,
    ),
]
