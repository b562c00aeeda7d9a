"""Lesson 4: the ROS 2 package, and what data_files does."""

from ._cells import Lesson, code, md

LESSON = Lesson(
    "04",
    {"fr": "le-paquet-ros2", "en": "the-ros2-package"},
    {"fr": "4 · Le paquet ROS 2", "en": "4 · The ROS 2 package"},
)

LESSON.cells = [
    md(
        """
        Dans ROS 2, la description du robot vit dans un **paquet** (`bras_description`). `colcon
        build` l'installe ; `ros2 launch` le retrouve ensuite dans le dossier `share/` de
        l'installation. `bras_kit` écrit ce paquet pour vous ; regardons ce qu'il contient, puis
        provoquons la panne la plus fréquente du tutoriel : l'URDF qui n'est pas installé.
        """,
        """
        In ROS 2 the robot's description lives in a **package** (`bras_description`). `colcon build`
        installs it; `ros2 launch` then finds it in the install's `share/` folder. `bras_kit` writes
        this package for you; let us look inside, then cause the tutorial's most common failure:
        the URDF that never got installed.
        """,
    ),
    code(
        """
        import shutil
        import subprocess
        import sys
        import tempfile
        from pathlib import Path

        import bras_kit
        from bras_kit.scaffold import scaffold_package

        bras_kit.set_language("@LANG@")  # the library's messages and picture words in this notebook's language
        work = Path(tempfile.mkdtemp(prefix="bras-paquet-"))
        package = work / "bras_description"
        scaffold_package(package, lang="@LANG@")

        for path in sorted(package.rglob("*")):
            if path.is_file():
                print(path.relative_to(work))
        """
    ),
    md(
        """
        | fichier | rôle |
        |---|---|
        | `package.xml` | l'identité du paquet et ce dont il a besoin pour tourner |
        | `setup.py` | comment construire et **quoi copier où** (`data_files`) |
        | `resource/bras_description` | un fichier vide : le marqueur qui rend le paquet visible à ROS 2 |
        | `urdf/bras.urdf` | la description du bras (leçon 1) |
        | `launch/*.launch.py` | démarre `robot_state_publisher`, les curseurs et RViz |
        | `bras_description/animation.py` | le nœud qui anime le bras (leçon 5) |

        ## package.xml
        """,
        """
        | file | purpose |
        |---|---|
        | `package.xml` | the package's identity and what it needs at run time |
        | `setup.py` | how to build it and **what to copy where** (`data_files`) |
        | `resource/bras_description` | an empty file: the marker that makes the package visible to ROS 2 |
        | `urdf/bras.urdf` | the arm's description (lesson 1) |
        | `launch/*.launch.py` | starts `robot_state_publisher`, the sliders and RViz |
        | `bras_description/animation.py` | the node that moves the arm (lesson 5) |

        ## package.xml
        """,
    ),
    code(
        """
        print((package / "package.xml").read_text())
        """
    ),
    md(
        """
        Les `exec_depend` nomment les paquets ROS utilisés **au lancement** : sans eux, `rosdep`
        n'installerait pas `robot_state_publisher` ni `rviz2` sur une machine neuve.

        ## setup.py et data_files

        `data_files` est une liste de couples *(dossier de destination, fichiers sources)*. Rien
        d'autre n'est copié : un fichier absent de cette liste n'existe pas pour ROS 2. Dans le
        `setup.py` généré, chaque couple est fabriqué par une petite fonction `installed()`, qui
        arrête aussi la construction si le dossier est vide.
        """,
        """
        The `exec_depend` entries name the ROS packages used **at launch**: without them `rosdep`
        would not install `robot_state_publisher` or `rviz2` on a fresh machine.

        ## setup.py and data_files

        `data_files` is a list of pairs *(destination folder, source files)*. Nothing else is
        copied: a file missing from that list does not exist as far as ROS 2 is concerned. In the
        generated `setup.py` each pair is made by a small function, `installed()`, which also stops
        the build when the folder is empty.
        """,
    ),
    code(
        """
        setup_py = (package / "setup.py").read_text()
        print(setup_py)
        """
    ),
    md(
        """
        ## Le fichier de lancement

        Il demande à ROS 2 le dossier `share/` du paquet (`get_package_share_directory`) et y lit
        l'URDF. C'est là que `data_files` l'a copié… si on ne l'a pas oublié.
        """,
        """
        ## The launch file

        It asks ROS 2 for the package's `share/` folder (`get_package_share_directory`) and reads
        the URDF there. That is where `data_files` copied it… unless it was forgotten.
        """,
    ),
    code(
        """
        launch_file = next((package / "launch").glob("*.launch.py"))
        print(launch_file.read_text())
        """
    ),
    md(
        """
        ## Installer comme colcon

        Pour un paquet `ament_python`, `colcon build` fait construire le paquet par setuptools et
        copie le résultat dans `install/`. `pip install --target` fait le même travail sans ROS :
        le code Python et, surtout, les `data_files` sous `share/`.
        """,
        """
        ## Install it like colcon

        For an `ament_python` package, `colcon build` has setuptools build the package and copies
        the result into `install/`. `pip install --target` does the same job without ROS: the
        Python code and, above all, the `data_files` under `share/`.
        """,
    ),
    code(
        """
        def install(source, target):
            # --no-build-isolation: use the installed setuptools, no download
            result = subprocess.run(
                [sys.executable, "-m", "pip", "install", "--quiet", "--no-deps", "--no-build-isolation", "--no-compile",
                 "--target", str(target), str(source)],
                capture_output=True, text=True)
            if result.returncode != 0:
                print(result.stderr)
            shutil.rmtree(Path(source) / "build", ignore_errors=True)
            return result.returncode


        def share_files(target):
            share = Path(target) / "share" / "bras_description"
            return sorted(p.relative_to(share).as_posix() for p in share.rglob("*") if p.is_file())


        install(package, work / "install-ok")
        print(share_files(work / "install-ok"))
        """
    ),
    md(
        """
        Faisons ce que fait le fichier de lancement : chercher l'URDF dans `share/`, le lire.
        """,
        """
        Now do what the launch file does: look for the URDF under `share/` and read it.
        """,
    ),
    code(
        """
        def launch_reads_urdf(target):
            urdf = Path(target) / "share" / "bras_description" / "urdf" / "bras.urdf"
            try:
                robot = bras_kit.load(urdf)
            except bras_kit.BrasKitError as error:
                print("le lancement échouerait :", bras_kit.say(error))
                return None
            print("URDF trouvé :", [link.name for link in robot.links])
            return robot


        found = launch_reads_urdf(work / "install-ok")
        """,
        """
        def launch_reads_urdf(target):
            urdf = Path(target) / "share" / "bras_description" / "urdf" / "bras.urdf"
            try:
                robot = bras_kit.load(urdf)
            except bras_kit.BrasKitError as error:
                print("the launch would fail:", bras_kit.say(error))
                return None
            print("URDF found:", [link.name for link in robot.links])
            return robot


        found = launch_reads_urdf(work / "install-ok")
        """,
    ),
    md(
        """
        ## La panne : data_files sans la ligne urdf

        Copions le paquet et retirons la ligne qui installe `urdf/` — c'est l'oubli de l'étape 5
        du tutoriel. Le paquet s'installe **sans erreur** : c'est ce qui rend la panne
        déroutante.
        """,
        """
        ## The failure: data_files without the urdf line

        Copy the package and remove the line that installs `urdf/` — the slip of the tutorial's
        step 5. The package installs **without any error**: that is what makes this failure so
        confusing.
        """,
    ),
    code(
        """
        broken = work / "broken" / "bras_description"
        shutil.copytree(package, broken)
        lines = (broken / "setup.py").read_text().splitlines(keepends=True)
        kept = [line for line in lines if not ("'urdf'" in line or '"urdf"' in line)]
        print("ligne retirée :", *[line for line in lines if line not in kept])
        (broken / "setup.py").write_text("".join(kept))

        print("code de sortie de pip :", install(broken, work / "install-broken"))
        print(share_files(work / "install-broken"))
        found = launch_reads_urdf(work / "install-broken")
        """,
        """
        broken = work / "broken" / "bras_description"
        shutil.copytree(package, broken)
        lines = (broken / "setup.py").read_text().splitlines(keepends=True)
        kept = [line for line in lines if not ("'urdf'" in line or '"urdf"' in line)]
        print("removed line:", *[line for line in lines if line not in kept])
        (broken / "setup.py").write_text("".join(kept))

        print("pip exit code:", install(broken, work / "install-broken"))
        print(share_files(work / "install-broken"))
        found = launch_reads_urdf(work / "install-broken")
        """,
    ),
    md(
        """
        Le dossier `urdf/` manque dans `share/` : sur une vraie machine, `ros2 launch` s'arrête
        sur le message `file not found` (fichier introuvable). Le correctif est celui du tutoriel : remettre la ligne dans
        `data_files` et reconstruire (`colcon build`).

        La vérification à faire avant de partir sur une machine ROS : chaque dossier du paquet
        dont le lancement a besoin se retrouve-t-il dans `share/` ?
        """,
        """
        The `urdf/` folder is missing from `share/`: on a real machine `ros2 launch` stops with a
        *file not found*. The fix is the tutorial's: put the line back in `data_files` and rebuild
        (`colcon build`).

        The check to make before leaving for a ROS machine: does every folder of the package the
        launch needs end up in `share/`?
        """,
    ),
    code(
        """
        for target in ("install-ok", "install-broken"):
            installed = {path.split("/")[0] for path in share_files(work / target)}
            missing = [folder for folder in ("urdf", "launch", "rviz") if folder not in installed]
            print(f"{target:15s}", "manque : " + ", ".join(missing) if missing else "complet")
        """,
        """
        for target in ("install-ok", "install-broken"):
            installed = {path.split("/")[0] for path in share_files(work / target)}
            missing = [folder for folder in ("urdf", "launch", "rviz") if folder not in installed]
            print(f"{target:15s}", "missing: " + ", ".join(missing) if missing else "complete")
        """,
    ),
    md(
        """
        Pour emmener ce paquet sur une vraie machine ROS 2 Jazzy (`colcon build`, `source`,
        `ros2 launch`), voir la page « Vers une vraie machine ROS 2 » de la documentation.
        """,
        """
        To take this package to a real ROS 2 Jazzy machine (`colcon build`, `source`,
        `ros2 launch`), see the "To a real ROS 2 machine" page of the documentation.
        """,
    ),
    code(
        """
        shutil.rmtree(work)  # tidy up the temporary folder
        """
    ),
]
