"""Lesson 8: the pitfalls table, row by row: break, detect, fix."""

from ._cells import Lesson, code, md

LESSON = Lesson(
    "08",
    {"fr": "labo-des-pieges", "en": "pitfalls-lab"},
    {"fr": "8 · Le labo des pièges", "en": "8 · The pitfalls lab"},
)

LESSON.cells = [
    md(
        """
        Le tutoriel liste cinq pannes fréquentes. Ici, on les **provoque** exprès, une par une,
        on regarde comment elles se voient sans ROS, puis on répare.

        | # | symptôme | cause |
        |---|---|---|
        | 1 | RViz reste vide | Fixed Frame ou RobotModel mal réglés |
        | 2 | le bras s'affiche mais ne bouge pas | personne ne publie sur `/joint_states` |
        | 3 | `file not found` au lancement | l'URDF n'est pas installé (`data_files`) |
        | 4 | segments mal placés | `origin` d'une articulation incohérente avec la longueur du parent |
        | 5 | les articulations dépassent | angles publiés hors des `limit` |

        Les pannes 4 et 5 sont dans l'URDF ou dans le mouvement : le validateur de `bras_kit` les
        trouve. Les pannes 1 à 3 sont dans la configuration de RViz et du paquet : on fait la
        vérification équivalente sur les fichiers que `bras_kit` génère.
        """,
        """
        The tutorial lists five common failures. Here we **cause** them on purpose, one by one, see
        how each shows up without ROS, then fix it.

        | # | symptom | cause |
        |---|---|---|
        | 1 | RViz stays empty | Fixed Frame or RobotModel set wrong |
        | 2 | the arm shows but does not move | nobody publishes on `/joint_states` |
        | 3 | *file not found* at launch | the URDF is not installed (`data_files`) |
        | 4 | segments in the wrong place | a joint's `origin` disagrees with its parent's length |
        | 5 | joints go past their stops | angles published outside the `limit`s |

        Failures 4 and 5 live in the URDF or the motion: `bras_kit`'s validator finds them.
        Failures 1 to 3 live in the RViz and package configuration: we make the equivalent check
        on the files `bras_kit` generates.
        """,
    ),
    code(
        """
        import importlib.util
        import math
        import re
        import subprocess
        import sys
        import tempfile
        from pathlib import Path

        import matplotlib.pyplot as plt
        import numpy as np
        import yaml

        import bras_kit
        from bras_kit.core.i18n import say
        from bras_kit.motion import formula_motion, sample, tutorial_motion
        from bras_kit.render import Renderer
        from bras_kit.scaffold import scaffold_package
        from bras_kit.validate import validate

        bras_kit.set_language("fr")  # messages, titres et axes de la bibliothèque en français
        robot = bras_kit.arm()
        tree = bras_kit.tf_tree(robot)
        good_urdf = bras_kit.arm_urdf()
        package = Path(tempfile.mkdtemp(prefix="pieges-")) / "bras_description"
        scaffold_package(package, lang="@LANG@")


        SEVERITE = {"error": "erreur", "warning": "avertissement", "info": "info"}


        def show(findings):
            for f in findings:
                print(f"{f.code} [{SEVERITE[f.severity]}] ligne {f.line} : {f.text('@LANG@')}")
                print("    ->", f.hint_text("@LANG@"))
            if not findings:
                print("aucun problème trouvé")


        def load_text(text, name):
            Path(name).write_text(text, encoding="utf-8")
            return bras_kit.load(name)
        """,
        """
        import importlib.util
        import math
        import re
        import subprocess
        import sys
        import tempfile
        from pathlib import Path

        import matplotlib.pyplot as plt
        import numpy as np
        import yaml

        import bras_kit
        from bras_kit.core.i18n import say
        from bras_kit.motion import formula_motion, sample, tutorial_motion
        from bras_kit.render import Renderer
        from bras_kit.scaffold import scaffold_package
        from bras_kit.validate import validate

        bras_kit.set_language("en")  # the library's messages, titles and axis labels in English
        robot = bras_kit.arm()
        tree = bras_kit.tf_tree(robot)
        good_urdf = bras_kit.arm_urdf()
        package = Path(tempfile.mkdtemp(prefix="pitfalls-")) / "bras_description"
        scaffold_package(package, lang="@LANG@")


        def show(findings):
            for f in findings:
                print(f"{f.code} [{f.severity}] line {f.line}: {f.text('@LANG@')}")
                print("    ->", f.hint_text("@LANG@"))
            if not findings:
                print("no problem found")


        def load_text(text, name):
            Path(name).write_text(text, encoding="utf-8")
            return bras_kit.load(name)
        """,
    ),
    md(
        """
        ## 1. RViz reste vide

        RViz a besoin de deux réglages : un **Fixed Frame** qui existe dans l'arbre TF (la racine,
        `base`), et un affichage **RobotModel** qui lit l'URDF sur le topic où
        `robot_state_publisher` le publie, `/robot_description`. Le paquet généré contient un
        fichier `.rviz` (du YAML) avec les deux ; vérifions-le comme RViz le lirait :
        """,
        """
        ## 1. RViz stays empty

        RViz needs two settings: a **Fixed Frame** that exists in the TF tree (the root, `base`),
        and a **RobotModel** display reading the URDF from the topic `robot_state_publisher`
        publishes it on, `/robot_description`. The generated package holds an `.rviz` file (YAML)
        with both; let us check it the way RViz would read it:
        """,
    ),
    code(
        """
        def check_rviz(config, tree):
            manager = config["Visualization Manager"]
            fixed = manager["Global Options"]["Fixed Frame"]
            models = [d for d in manager["Displays"] if d["Class"].endswith("/RobotModel")]
            topic = models[0]["Description Topic"]["Value"] if models else None
            checks = {
                f"Fixed Frame '{fixed}' est un repère de l'arbre": fixed in tree.links,
                "il y a un affichage RobotModel": bool(models),
                f"RobotModel lit '{topic}' (= /robot_description)": topic == "/robot_description",
            }
            for label, ok in checks.items():
                print("✓" if ok else "✗", label)
            return all(checks.values())


        rviz_file = package / "rviz" / "bras_description.rviz"
        config = yaml.safe_load(rviz_file.read_text())
        check_rviz(config, tree)
        """,
        """
        def check_rviz(config, tree):
            manager = config["Visualization Manager"]
            fixed = manager["Global Options"]["Fixed Frame"]
            models = [d for d in manager["Displays"] if d["Class"].endswith("/RobotModel")]
            topic = models[0]["Description Topic"]["Value"] if models else None
            checks = {
                f"Fixed Frame '{fixed}' is a frame of the tree": fixed in tree.links,
                "there is a RobotModel display": bool(models),
                f"RobotModel reads '{topic}' (= /robot_description)": topic == "/robot_description",
            }
            for label, ok in checks.items():
                print("✓" if ok else "✗", label)
            return all(checks.values())


        rviz_file = package / "rviz" / "bras_description.rviz"
        config = yaml.safe_load(rviz_file.read_text())
        check_rviz(config, tree)
        """,
    ),
    md(
        """
        **On casse** : la valeur par défaut de RViz, `map`, et un topic mal tapé — exactement la
        fenêtre vide du tutoriel. **On répare** : la racine de l'arbre, et le bon topic.
        """,
        """
        **Break it**: RViz's default, `map`, and a mistyped topic — exactly the tutorial's empty
        window. **Fix it**: the tree's root, and the right topic.
        """,
    ),
    code(
        """
        config["Visualization Manager"]["Global Options"]["Fixed Frame"] = "map"
        model = next(d for d in config["Visualization Manager"]["Displays"] if d["Class"].endswith("/RobotModel"))
        model["Description Topic"]["Value"] = "/robot_desc"
        print(check_rviz(config, tree), "\\n")

        config["Visualization Manager"]["Global Options"]["Fixed Frame"] = tree.root
        model["Description Topic"]["Value"] = "/robot_description"
        print(check_rviz(config, tree))
        """
    ),
    md(
        """
        Troisième façon d'avoir un RViz vide : un modèle sans aucune forme à dessiner. Celle-là
        est dans l'URDF, et le validateur la voit :
        """,
        """
        A third way to get an empty RViz: a model with no shape to draw. That one is in the URDF,
        and the validator sees it:
        """,
    ),
    code(
        """
        invisible = load_text(re.sub(r"<visual>.*?</visual>", "", good_urdf, flags=re.S), "invisible.urdf")
        show(validate(invisible, lang="@LANG@", select=["BK3"]))
        """
    ),
    md(
        """
        ## 2. Le bras s'affiche mais ne bouge pas

        `robot_state_publisher` ne bouge une articulation que s'il reçoit son angle sur `/joint_states`,
        **reconnu par son nom**. Personne ne publie, ou les noms sont faux : le bras reste figé à
        zéro, sans le moindre message d'erreur.

        Le nœud d'animation du paquet généré sépare ROS et calcul : `motion.py` ne contient que
        les mathématiques. On peut donc l'exécuter ici et le comparer au mouvement du tutoriel :
        """,
        """
        ## 2. The arm shows but does not move

        `robot_state_publisher` only moves a joint when it gets its angle on `/joint_states`,
        **matched by name**. Nobody publishes, or the names are wrong: the arm stays frozen at
        zero, without a single error message.

        The generated package's animation node keeps ROS and maths apart: `motion.py` holds only
        the maths. So we can run it here and compare it with the tutorial's motion:
        """,
    ),
    code(
        """
        spec = importlib.util.spec_from_file_location("node_motion", package / "bras_description" / "motion.py")
        node_motion = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(node_motion)

        states = sample(tutorial_motion(robot), duration=10.0, rate=20.0)
        published = np.array([node_motion.joint_positions(t) for t in states.times])
        print("noms publiés :", node_motion.JOINT_NAMES, " articulations du modèle :", list(tree.dof))
        print("mêmes angles que le tutoriel :", np.allclose(published, states.positions))
        print("le bras bouge :", np.ptp(published, axis=0))
        """,
        """
        spec = importlib.util.spec_from_file_location("node_motion", package / "bras_description" / "motion.py")
        node_motion = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(node_motion)

        states = sample(tutorial_motion(robot), duration=10.0, rate=20.0)
        published = np.array([node_motion.joint_positions(t) for t in states.times])
        print("names published:", node_motion.JOINT_NAMES, " model's joints:", list(tree.dof))
        print("same angles as the tutorial:", np.allclose(published, states.positions))
        print("the arm moves over:", np.ptp(published, axis=0))
        """,
    ),
    md(
        """
        **On casse** : un nœud qui publie des noms anglais (`shoulder`, `elbow`). ROS les
        ignorerait en silence ; `bras_kit` refuse et dit quels noms existent. **On répare** : les
        noms des articulations de l'URDF.
        """,
        """
        **Break it**: a node publishing English names (`shoulder`, `elbow`). ROS would ignore them
        silently; `bras_kit` refuses and says which names exist. **Fix it**: the URDF's joint
        names.
        """,
    ),
    code(
        """
        try:
            formula_motion(robot, ["shoulder=0.8*sin(t)", "elbow=1.2*sin(0.7*t)"])
        except bras_kit.BrasKitError as error:
            print(say(error, "@LANG@"))

        fixed = sample(formula_motion(robot, ["epaule=0.8*sin(t)", "coude=1.2*sin(0.7*t)"]), duration=10.0)
        print(np.allclose(fixed.positions, states.positions))
        """
    ),
    md(
        """
        ## 3. `file not found` (fichier introuvable) au lancement

        Le fichier de lancement lit `share/bras_description/urdf/bras.urdf` et
        `share/bras_description/rviz/…` ; seuls les dossiers listés dans `data_files` de
        `setup.py` y sont copiés (la leçon 4 le montre avec une vraie installation). Plutôt que
        de relire `setup.py` à l'œil, on demande au validateur de vérifier tout le paquet, comme
        on le taperait dans un terminal : `bras-kit validate bras_description/`. Il lit
        `setup.py`, `package.xml`, le fichier de lancement, la configuration RViz et le nœud sans
        rien exécuter, et dit pour chaque problème le fichier, la ligne et la correction.
        """,
        """
        ## 3. *file not found* at launch

        The launch file reads `share/bras_description/urdf/bras.urdf` and
        `share/bras_description/rviz/…`; only the folders listed in `setup.py`'s `data_files` get
        copied there (lesson 4 shows it with a real install). Rather than reading `setup.py` by eye,
        we ask the validator to check the whole package, as one would type in a terminal:
        `bras-kit validate bras_description/`. It reads `setup.py`, `package.xml`, the launch file,
        the RViz configuration and the node without running anything, and gives for each problem
        the file, the line and the fix.
        """,
    ),
    code(
        """
        def validate_folder(folder):
            result = subprocess.run([sys.executable, "-m", "bras_kit", "validate", str(folder), "--lang", "@LANG@"],
                                    capture_output=True, text=True)
            print(result.stdout)


        validate_folder(package)
        """
    ),
    code(
        """
        setup_file = package / "setup.py"
        setup_text = setup_file.read_text()
        setup_file.write_text("".join(line for line in setup_text.splitlines(keepends=True) if "'urdf'" not in line))
        validate_folder(package)
        setup_file.write_text(setup_text)
        validate_folder(package)
        """
    ),
    md(
        """
        Le même outil lit le nœud sans le lancer. **On casse** : un `s` oublié dans le nom du
        topic, `'joint_state'`. Aucune erreur ne s'afficherait nulle part avec ROS : le bras
        resterait immobile dans RViz. **On répare** : `'joint_states'`.
        """,
        """
        The same tool reads the node without running it. **Break it**: an `s` forgotten in the
        topic's name, `'joint_state'`. ROS would show no error anywhere: the arm would just stay
        still in RViz. **Fix it**: `'joint_states'`.
        """,
    ),
    code(
        """
        node_file = package / "bras_description" / "animation.py"
        node_text = node_file.read_text()
        node_file.write_text(node_text.replace("'joint_states', 10", "'joint_state', 10"))
        validate_folder(package)
        node_file.write_text(node_text)
        """
    ),
    md(
        """
        Le correctif : remettre la ligne dans `data_files`, puis `colcon build` de nouveau. (Le
        `setup.py` généré va plus loin : si le dossier `urdf/` est vide, la construction s'arrête
        avec un message, au lieu d'échouer plus tard au lancement.)

        ## 4. Segments mal placés

        L'origine du `coude` doit être au bout du bras, `z = 0.6`. **On casse** : `z = 0.4`.
        """,
        """
        The fix: put the line back in `data_files`, then `colcon build` again. (The generated
        `setup.py` goes further: if the `urdf/` folder is empty, the build stops with a message
        instead of failing later at launch.)

        ## 4. Segments in the wrong place

        The `coude` origin must be at the tip of the upper arm, `z = 0.6`. **Break it**: `z = 0.4`.
        """,
    ),
    code(
        """
        short_elbow = load_text(good_urdf.replace('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 0.4"/>'), "coude_court.urdf")
        show(validate(short_elbow, lang="@LANG@", select=["BK3"]))


        def front_view(ax, arm, pose, distance=3.0):
            \"""Le bras vu de face, sur des axes en mètres (ceux du plan y = 0, comme à la leçon 1).\"""
            with Renderer(arm, fit=pose, view="front", distance=distance, size=(360, 360)) as renderer:
                picture = renderer.render(pose)
                camera = renderer.camera
            x, y, z = camera.pose[:3, 3]  # la caméra est à -y mètres du plan y = 0
            half = -y * math.tan(camera.yfov / 2)
            ax.imshow(picture, extent=(x - half, x + half, z - half, z + half))


        fig, axes = plt.subplots(1, 2, figsize=(8, 4.5), sharex=True, sharey=True)  # un seul cadrage pour les deux images
        for ax, (title, model) in zip(axes, [("z = 0.4", short_elbow), ("z = 0.6", robot)]):
            front_view(ax, model, {"coude": 1.0})
            ax.set_title(title)
            ax.set_xlabel("x (m)")
        axes[0].set_ylabel("z (m)")
        axes[0].set_xlim(-0.4, 0.9)
        axes[0].set_ylim(-0.15, 1.3)
        plt.show()
        """,
        """
        short_elbow = load_text(good_urdf.replace('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 0.4"/>'), "coude_court.urdf")
        show(validate(short_elbow, lang="@LANG@", select=["BK3"]))


        def front_view(ax, arm, pose, distance=3.0):
            \"""The arm seen from the front, on axes in metres (those of the plane y = 0, as in lesson 1).\"""
            with Renderer(arm, fit=pose, view="front", distance=distance, size=(360, 360)) as renderer:
                picture = renderer.render(pose)
                camera = renderer.camera
            x, y, z = camera.pose[:3, 3]  # the camera is -y metres from the plane y = 0
            half = -y * math.tan(camera.yfov / 2)
            ax.imshow(picture, extent=(x - half, x + half, z - half, z + half))


        fig, axes = plt.subplots(1, 2, figsize=(8, 4.5), sharex=True, sharey=True)  # one framing for both pictures
        for ax, (title, model) in zip(axes, [("z = 0.4", short_elbow), ("z = 0.6", robot)]):
            front_view(ax, model, {"coude": 1.0})
            ax.set_title(title)
            ax.set_xlabel("x (m)")
        axes[0].set_ylabel("z (m)")
        axes[0].set_xlim(-0.4, 0.9)
        axes[0].set_ylim(-0.15, 1.3)
        plt.show()
        """,
    ),
    md(
        """
        À gauche, l'avant-bras sort du milieu du bras. Le message donne la ligne et l'origine à
        écrire. La faute voisine : la **forme** d'un segment centrée sur l'articulation au lieu de partir
        de lui (l'`origin` du `<visual>` oubliée) — la moitié du bras passe sous l'épaule :
        """,
        """
        On the left, the forearm comes out of the middle of the upper arm. The message gives the
        line and the origin to write. The neighbouring mistake: a link's **shape** centred on the
        joint instead of starting from it (the `<visual>`'s `origin` forgotten) — half the upper
        arm sinks below the shoulder:
        """,
    ),
    code(
        """
        centred = load_text(good_urdf.replace('<origin xyz="0 0 0.3"/>', '<origin xyz="0 0 0"/>', 1), "bras_centre.urdf")
        show(validate(centred, lang="@LANG@", select=["BK3"]))
        print()
        show(validate(robot, lang="@LANG@", select=["BK3"]))  # repaired: the generated arm
        """
    ),
    md(
        """
        ## 5. Les articulations dépassent

        Un angle hors butée, l'URDF ne l'empêche pas : `robot_state_publisher` affiche ce qu'on
        lui envoie. Le validateur vérifie une pose (`pose=`) ou tout un mouvement (`states=`),
        positions **et** vitesses. **On casse** : `coude = 2.5 sin t`.
        """,
        """
        ## 5. Joints go past their stops

        The URDF does not prevent an angle past a stop: `robot_state_publisher` shows whatever it
        is sent. The validator checks a pose (`pose=`) or a whole motion (`states=`), positions
        **and** speeds. **Break it**: `coude = 2.5 sin t`.
        """,
    ),
    code(
        """
        show(validate(robot, pose={"epaule": 2.0}, lang="@LANG@", select=["BK3"]))
        print()
        wild = sample(formula_motion(robot, ["epaule=0.8*sin(t)", "coude=2.5*sin(t)"]), duration=10.0)
        show(validate(robot, states=wild, lang="@LANG@", select=["BK3"]))
        """
    ),
    code(
        """
        from IPython.display import Image, display

        from bras_kit.diagrams import plot_motion

        plot_motion(robot, wild, path="depassement.png")
        display(Image(filename="depassement.png"))
        """
    ),
    md(
        """
        **On répare** : une amplitude dans les butées **et** une vitesse de pointe
        (`amplitude × fréquence`) sous 1 rad/s — ce que fait le mouvement du tutoriel,
        `1.2 sin 0.7t` : 1,2 < 2 et 0,84 < 1.
        """,
        """
        **Fix it**: an amplitude within the stops **and** a peak speed (`amplitude × frequency`)
        under 1 rad/s — what the tutorial's motion does, `1.2 sin 0.7t`: 1.2 < 2 and 0.84 < 1.
        """,
    ),
    code(
        """
        show(validate(robot, states=states, lang="@LANG@", select=["BK3"]))
        """
    ),
    md(
        """
        ## En résumé

        | # | panne | comment la voir sans ROS |
        |---|---|---|
        | 1 | RViz vide | le `.rviz` : Fixed Frame dans l'arbre, RobotModel sur `/robot_description` ; BK307 |
        | 2 | rien ne bouge | les noms publiés = `tree.dof` ; le calcul du nœud exécuté hors ROS |
        | 3 | `file not found` | chaque dossier lu par le lancement est dans `data_files` (leçon 4) |
        | 4 | segments mal placés | BK301, BK302 |
        | 5 | butées dépassées | BK303 (pose), BK304 et BK305 (mouvement) |

        `bras-kit validate` fait les vérifications de l'URDF en ligne de commande, et
        `bras-kit explain BK301` explique une règle en détail.
        """,
        """
        ## Summary

        | # | failure | how to see it without ROS |
        |---|---|---|
        | 1 | empty RViz | the `.rviz` file: Fixed Frame in the tree, RobotModel on `/robot_description`; BK307 |
        | 2 | nothing moves | the names published = `tree.dof`; the node's maths run outside ROS |
        | 3 | *file not found* | every folder the launch file reads is in `data_files` (lesson 4) |
        | 4 | segments misplaced | BK301, BK302 |
        | 5 | stops exceeded | BK303 (pose), BK304 and BK305 (motion) |

        `bras-kit validate` runs the URDF checks from the command line, and `bras-kit explain BK301`
        explains a rule in detail.
        """,
    ),
]
