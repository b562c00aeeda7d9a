"""Lesson 6 (exercise): add a wrist, by hand and with wrist=True; validate; animate three joints."""

from ._cells import Lesson, code, md

LESSON = Lesson(
    "06",
    {"fr": "exercice-poignet", "en": "exercise-wrist"},
    {"fr": "6 · Exercice : ajouter un poignet", "en": "6 · Exercise: add a wrist"},
)

SOLUTION = Lesson(
    "06",
    {"fr": "solution-poignet", "en": "solution-wrist"},
    {"fr": "6 · Solution : le poignet", "en": "6 · Solution: the wrist"},
    folder="solutions",
)

SETUP = code(
    """
    from pathlib import Path

    import numpy as np

    import bras_kit
    from bras_kit.validate import validate

    bras_kit.set_language("fr")  # messages, titres et axes de la bibliothèque en français
    SEVERITE = {"error": "erreur", "warning": "avertissement", "info": "info"}


    def show(findings):
        if not findings:
            print("aucun problème trouvé")
        for f in findings:
            print(f"{f.code} [{SEVERITE[f.severity]}] {f.text('@LANG@')}")
            if f.hint:
                print("    ->", f.hint_text("@LANG@"))


    def check_wrist(robot):
        # Chaque attente de l'exercice, cochée ou non.
        joint = robot.joint("poignet")
        link = robot.link("main")
        tests = {
            "un segment 'main'": link is not None,
            "une articulation 'poignet' revolute": joint is not None and joint.type == "revolute",
            "parent avant_bras, enfant main": joint is not None and (joint.parent, joint.child) == ("avant_bras", "main"),
            "origine au bout de l'avant-bras (z = 0.5)": joint is not None and np.allclose(joint.origin.xyz, (0, 0, 0.5)),
            "axe y": joint is not None and joint.axis is not None and np.allclose(joint.axis, (0, 1, 0)),
            "des butées": joint is not None and joint.limit is not None and joint.limit.upper is not None,
        }
        for label, ok in tests.items():
            print("✓" if ok else "✗", label)
        return all(tests.values())
    """,
    """
    from pathlib import Path

    import numpy as np

    import bras_kit
    from bras_kit.validate import validate

    bras_kit.set_language("en")  # the library's messages, titles and axis labels in English

    def show(findings):
        if not findings:
            print("no problem found")
        for f in findings:
            print(f"{f.code} [{f.severity}] {f.text('@LANG@')}")
            if f.hint:
                print("    ->", f.hint_text("@LANG@"))


    def check_wrist(robot):
        # Each expectation of the exercise, ticked or not.
        joint = robot.joint("poignet")
        link = robot.link("main")
        tests = {
            "a link 'main'": link is not None,
            "a revolute joint 'poignet'": joint is not None and joint.type == "revolute",
            "parent avant_bras, child main": joint is not None and (joint.parent, joint.child) == ("avant_bras", "main"),
            "origin at the forearm's tip (z = 0.5)": joint is not None and np.allclose(joint.origin.xyz, (0, 0, 0.5)),
            "y axis": joint is not None and joint.axis is not None and np.allclose(joint.axis, (0, 1, 0)),
            "limits": joint is not None and joint.limit is not None and joint.limit.upper is not None,
        }
        for label, ok in tests.items():
            print("✓" if ok else "✗", label)
        return all(tests.values())
    """,
)

BUILD = code(
    """
    text = bras_kit.arm_urdf().replace("</robot>", wrist_xml + "\\n</robot>")
    Path("bras_poignet.urdf").write_text(text, encoding="utf-8")
    mine = bras_kit.load("bras_poignet.urdf")
    done = check_wrist(mine)
    show(validate(mine, lang="@LANG@"))
    """
)

LESSON.cells = [
    md(
        """
        Le tutoriel se termine par un défi : ajouter une troisième articulation, un **poignet**
        au bout de l'avant-bras, puis l'animer. Trois étapes :

        1. à la main, dans l'URDF : un segment et une articulation de plus ;
        2. avec `bras_kit.arm(wrist=True)`, qui fait la même chose depuis le modèle xacro ;
        3. animer les trois articulations.

        La solution complète est dans `solutions/06-solution-poignet.ipynb` — essayez d'abord !
        """,
        """
        The tutorial ends with a challenge: add a third joint, a **wrist** at the tip of the
        forearm, then move it. Three steps:

        1. by hand, in the URDF: one more link and one more joint;
        2. with `bras_kit.arm(wrist=True)`, which does the same from the xacro template;
        3. move all three joints.

        The full solution is in `solutions/06-solution-wrist.ipynb` — try first!
        """,
    ),
    SETUP,
    md(
        """
        ## 1. À la main

        Écrivez dans la cellule suivante, en XML, ce qui manque pour le poignet :

        * un `<link name="main">` : la main, un pavé plus court que l'avant-bras (0,15 m de long,
          0,04 m de côté), dont la forme commence à l'origine du segment ;
        * un `<joint name="poignet" type="revolute">` : parent `avant_bras`, enfant `main`,
          une `origin` **au bout de l'avant-bras**, le même `axis` que les autres articulations, et des
          `limit` (par exemple ±1,57 rad, effort 5, vitesse 1,5).

        Pourquoi `main` et pas `poignet`, comme l'écrit la piste du tutoriel ? Le tutoriel nomme
        les segments d'après le corps (`bras`, `avant_bras`) et les articulations d'après ce qui
        plie (`epaule` fait bouger `bras`, `coude` fait bouger `avant_bras`) : le poignet fait
        bouger la main. Et surtout, RViz accepte un segment et une articulation du même nom, mais
        **Gazebo le refuse** : il convertit l'URDF en SDF, où segments et articulations partagent un
        seul espace de noms, et rejette tout le modèle (`Joint with non-unique name [poignet]`).
        L'articulation garde le nom `poignet`, celui que votre nœud publie dans `msg.name`. La fin
        de la leçon le montre.

        La cellule d'après colle votre texte avant `</robot>`, charge le fichier et coche ce qui
        est juste. Tant que la cellule est vide, tout est décoché : c'est normal.
        """,
        """
        ## 1. By hand

        Write in the next cell, in XML, what the wrist needs:

        * a `<link name="main">`: the hand, a box shorter than the forearm (0.15 m long, 0.04 m
          wide), whose shape starts at the link's origin;
        * a `<joint name="poignet" type="revolute">`: parent `avant_bras`, child `main`, an
          `origin` **at the forearm's tip**, the same `axis` as the other joints, and `limit`s
          (for example ±1.57 rad, effort 5, velocity 1.5).

        Why `main` and not `poignet`, as the tutorial's hint writes it? The tutorial names the
        links after the body (`bras`, `avant_bras`) and the joints after what bends (`epaule`
        moves `bras`, `coude` moves `avant_bras`): the wrist moves the hand, `main`. Above all,
        RViz accepts a link and a joint with one name, but **Gazebo refuses it**: it converts the
        URDF to SDF, where links and joints share one namespace, and rejects the whole model
        ("Joint with non-unique name [poignet]"). The joint keeps the name `poignet`, the one your
        node publishes in `msg.name`. The end of the lesson shows it.

        The cell after pastes your text before `</robot>`, loads the file and ticks what is right.
        While the cell is empty everything is unticked: that is expected.
        """,
    ),
    code(
        """
        wrist_xml = \"\"\"
          <!-- votre segment <link name="main"> et votre articulation <joint name="poignet"> ici -->
        \"\"\"
        """,
        """
        wrist_xml = \"\"\"
          <!-- your link "main" and joint "poignet" here -->
        \"\"\"
        """,
    ),
    BUILD,
    md(
        """
        ## 2. Avec le modèle : `wrist=True`

        Le modèle xacro du projet contient déjà le poignet, derrière un drapeau. Il passe la même
        grille :
        """,
        """
        ## 2. With the template: `wrist=True`

        The project's xacro template already holds the wrist, behind a flag. It passes the same
        checklist:
        """,
    ),
    code(
        """
        robot = bras_kit.arm(wrist=True)
        assert check_wrist(robot)
        show(validate(robot, lang="@LANG@"))
        tree = bras_kit.tf_tree(robot)
        print(tree.links, tree.dof)
        tip = bras_kit.fk(tree)["main"] @ [0, 0, 0.15, 1]
        print("bout de la main, bras droit :", tip[:3])
        """,
        """
        robot = bras_kit.arm(wrist=True)
        assert check_wrist(robot)
        show(validate(robot, lang="@LANG@"))
        tree = bras_kit.tf_tree(robot)
        print(tree.links, tree.dof)
        tip = bras_kit.fk(tree)["main"] @ [0, 0, 0.15, 1]
        print("hand tip, arm straight:", tip[:3])
        """,
    ),
    md(
        """
        Bras tendu, le bout est à `0.05 + 0.6 + 0.5 + 0.15 = 1.3` m : chaque origine d'articulation est
        la longueur du segment d'avant.

        ## 3. Animer trois articulations

        Dans le nœud du tutoriel, il faut ajouter `'poignet'` à `msg.name` **et** une troisième
        valeur à `msg.position` : les deux listes vont par paires. Ici, on ajoute une formule :
        """,
        """
        Arm straight, the tip is at `0.05 + 0.6 + 0.5 + 0.15 = 1.3` m: each joint's origin is the
        length of the segment before it.

        ## 3. Move three joints

        In the tutorial's node, `'poignet'` goes into `msg.name` **and** a third value into
        `msg.position`: the two lists go in pairs. Here we add one formula:
        """,
    ),
    code(
        """
        from IPython.display import Image, display

        from bras_kit.diagrams import plot_motion
        from bras_kit.motion import check_limits, formula_motion, sample
        from bras_kit.render import render_motion, save_gif

        three = formula_motion(robot, ["epaule=0.8*sin(t)", "coude=1.2*sin(0.7*t)", "poignet=1.0*sin(1.3*t)"])
        states = sample(three, duration=9.0, rate=10.0)
        print(states.names, check_limits(robot, states))
        save_gif(render_motion(robot, states, size=(320, 240)), "poignet.gif", fps=10)
        display(Image(filename="poignet.gif"))
        plot_motion(robot, states, path="poignet.png")
        display(Image(filename="poignet.png"))
        """
    ),
    md(
        """
        ## 4. Et Gazebo ?

        Écrivons le poignet comme la piste du tutoriel, segment et articulation tous deux
        `poignet`. RViz l'affiche sans broncher ; le validateur prévient (BK700), et avec
        `target="gazebo"` (ou `bras-kit validate --target gazebo`), c'est une erreur, comme pour
        Gazebo :
        """,
        """
        ## 4. And Gazebo?

        Let us write the wrist as the tutorial's hint does, link and joint both `poignet`. RViz
        shows it without a murmur; the validator warns (BK700), and with `target="gazebo"` (or
        `bras-kit validate --target gazebo`) it is an error, as it is for Gazebo:
        """,
    ),
    code(
        """
        piste = bras_kit.arm_urdf(wrist=True, inertials=True).replace('"main"', '"poignet"')
        Path("bras_piste.urdf").write_text(piste, encoding="utf-8")
        hint = bras_kit.load("bras_piste.urdf")
        for cible in (None, "gazebo"):
            for f in validate(hint, select=["BK700"], target=cible):
                print(f.code, SEVERITE[f.severity], "->", f.hint_text("fr"))
        gazebo = validate(bras_kit.arm(wrist=True, inertials=True), select=["BK700", "BK701", "BK702"], target="gazebo")
        print("avec main :", [f.code for f in gazebo] or "rien à redire")
        """,
        """
        hint_text = bras_kit.arm_urdf(wrist=True, inertials=True).replace('"main"', '"poignet"')
        Path("bras_piste.urdf").write_text(hint_text, encoding="utf-8")
        hint = bras_kit.load("bras_piste.urdf")
        for target in (None, "gazebo"):
            for f in validate(hint, select=["BK700"], target=target):
                print(f.code, f.severity, "->", f.hint_text("en"))
        gazebo = validate(bras_kit.arm(wrist=True, inertials=True), select=["BK700", "BK701", "BK702"], target="gazebo")
        print("with main:", [f.code for f in gazebo] or "nothing to say")
        """,
    ),
    md(
        """
        Avec `main`, Gazebo garde les quatre segments (`bras-kit gazebo --wrist --inertials` le
        montre). Sans `<inertial>`, il n'en garderait aucun : c'est la leçon 7.

        ## Pour aller plus loin

        * Donnez au poignet un axe `0 0 1` (rotation autour de l'avant-bras) : que voit-on ?
        * Que se passe-t-il si l'origine du poignet est `z = 0.6` ? (La leçon 8 montre ce que le
          validateur en dit.)
        """,
        """
        With `main`, Gazebo keeps all four links (`bras-kit gazebo --wrist --inertials` shows it).
        Without `<inertial>` it would keep none: that is lesson 7.

        ## Going further

        * Give the wrist the axis `0 0 1` (turning about the forearm): what do you see?
        * What happens if the wrist's origin is `z = 0.6`? (Lesson 8 shows what the validator says.)
        """,
    ),
]

SOLUTION.cells = [
    md(
        """
        Une réponse à l'exercice de la leçon 6. Le segment reprend le bloc `avant_bras`, en plus
        court ; l'articulation reprend le bloc `coude`, avec l'origine à la longueur de l'avant-bras.
        """,
        """
        One answer to lesson 6's exercise. The link copies the `avant_bras` block, shorter; the
        joint copies the `coude` block, with its origin at the forearm's length.
        """,
    ),
    SETUP,
    code(
        """
        wrist_xml = \"\"\"
          <link name="main">
            <visual>
              <origin xyz="0 0 0.075"/>
              <geometry><box size="0.04 0.04 0.15"/></geometry>
              <material name="vert"><color rgba="0.2 0.8 0.3 1"/></material>
            </visual>
          </link>
          <joint name="poignet" type="revolute">
            <parent link="avant_bras"/>
            <child link="main"/>
            <origin xyz="0 0 0.5"/>
            <axis xyz="0 1 0"/>
            <limit lower="-1.57" upper="1.57" effort="5" velocity="1.5"/>
          </joint>
        \"\"\"
        """
    ),
    BUILD,
    md(
        """
        Tout est coché, et le validateur ne trouve ni erreur ni avertissement (seulement une
        information : pas d'inerties, c'est la leçon 7 ; sans elles, Gazebo ne chargerait rien). Le résultat est le même, articulation par
        articulation, que celui du modèle avec `wrist=True` :
        """,
        """
        Everything is ticked, and the validator finds no error and no warning (only a note: no
        inertials, that is lesson 7; without them Gazebo would load nothing). The result is the same, joint for joint, as the template's
        with `wrist=True`:
        """,
    ),
    code(
        """
        assert done
        reference = bras_kit.arm(wrist=True)
        pose = {"epaule": 0.4, "coude": -0.9, "poignet": 1.1}
        ours = bras_kit.fk(bras_kit.tf_tree(mine), pose)
        theirs = bras_kit.fk(bras_kit.tf_tree(reference), pose)
        for link in ("bras", "avant_bras", "main"):
            assert np.allclose(ours[link], theirs[link])
            print(link, ours[link][:3, 3].round(4))
        """
    ),
    md(
        """
        Côté nœud d'animation, la liste des noms gagne `"poignet"` et la liste des angles une
        troisième valeur, dans le même ordre :

        ```python
        names = ["epaule", "coude", "poignet"]
        positions = [0.8 * sin(t), 1.2 * sin(0.7 * t), 1.0 * sin(1.3 * t)]
        ```
        """,
        """
        In the animation node, the list of names gains `"poignet"` and the list of angles a third
        value, in the same order:

        ```python
        names = ["epaule", "coude", "poignet"]
        positions = [0.8 * sin(t), 1.2 * sin(0.7 * t), 1.0 * sin(1.3 * t)]
        ```
        """,
    ),
]
