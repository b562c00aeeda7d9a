"""Lesson 7 (exercise): masses and inertias from the shapes; a bad inertia; why physics needs them."""

from ._cells import Lesson, code, md

LESSON = Lesson(
    "07",
    {"fr": "exercice-inerties", "en": "exercise-inertials"},
    {"fr": "7 · Exercice : masses et inerties", "en": "7 · Exercise: masses and inertias"},
)

SOLUTION = Lesson(
    "07",
    {"fr": "solution-inerties", "en": "solution-inertials"},
    {"fr": "7 · Solution : masses et inerties", "en": "7 · Solution: masses and inertias"},
    folder="solutions",
)

INTRO = md(
    r"""
    RViz ne simule rien : il dessine la géométrie aux angles qu'on lui publie. Un simulateur
    physique comme **Gazebo**, lui, calcule comment le bras tombe, accélère, force sur ses
    moteurs. Il lui faut, pour chaque segment, une balise `<inertial>` :

    * `mass` : la masse en kg ;
    * `origin` : le **centre de masse**, dans le repère du segment ;
    * `inertia` : le tenseur d'inertie autour de ce centre (six nombres, `ixx ixy ixz iyy iyz izz`).

    Pour un pavé plein de masse $m$ et de côtés $x, y, z$ :
    $I_{xx} = \frac{m}{12}(y^2+z^2)$, $I_{yy} = \frac{m}{12}(x^2+z^2)$, $I_{zz} = \frac{m}{12}(x^2+y^2)$.
    Pour un cylindre plein de rayon $r$ et de hauteur $h$ (axe z) :
    $I_{xx} = I_{yy} = \frac{m}{12}(3r^2+h^2)$, $I_{zz} = \frac{m r^2}{2}$.
    """,
    r"""
    RViz simulates nothing: it draws the geometry at the angles it is sent. A physics simulator
    such as **Gazebo** works out how the arm falls, speeds up, loads its motors. For that it needs
    an `<inertial>` element on every link:

    * `mass`: the mass in kg;
    * `origin`: the **centre of mass**, in the link's frame;
    * `inertia`: the inertia tensor about that centre (six numbers, `ixx ixy ixz iyy iyz izz`).

    For a solid box of mass $m$ and sides $x, y, z$:
    $I_{xx} = \frac{m}{12}(y^2+z^2)$, $I_{yy} = \frac{m}{12}(x^2+z^2)$, $I_{zz} = \frac{m}{12}(x^2+y^2)$.
    For a solid cylinder of radius $r$ and height $h$ (z axis):
    $I_{xx} = I_{yy} = \frac{m}{12}(3r^2+h^2)$, $I_{zz} = \frac{m r^2}{2}$.
    """,
)

_IMPORTS = """
import re
from pathlib import Path

import numpy as np

import bras_kit
from bras_kit.validate import validate
"""

_LANGUAGE = {
    "fr": 'bras_kit.set_language("fr")  # messages, titres et axes de la bibliothèque en français',
    "en": 'bras_kit.set_language("en")  # the library\'s messages, titles and axis labels in English',
}

_REFERENCE = {
    "fr": "reference = bras_kit.arm(inertials=True)  # la réponse du modèle, pour comparer",
    "en": "reference = bras_kit.arm(inertials=True)  # the template's answer, to compare with",
}

_SHOW = {
    "fr": """
SEVERITE = {"error": "erreur", "warning": "avertissement", "info": "info"}


def show(findings):
    if not findings:
        print("aucun problème trouvé")
    for f in findings:
        print(f"{f.code} [{SEVERITE[f.severity]}] {f.text('@LANG@')}")
        if f.hint:
            print("    ->", f.hint_text("@LANG@"))
""",
    "en": """
def show(findings):
    if not findings:
        print("no problem found")
    for f in findings:
        print(f"{f.code} [{f.severity}] {f.text('@LANG@')}")
        if f.hint:
            print("    ->", f.hint_text("@LANG@"))
""",
}

_COMPARE = {
    "fr": """
def compare(name, mine):
    expected = reference.link(name).inertial.inertia
    if mine is None:
        print(f"{name}: pas encore de réponse")
        return False
    ok = all(np.isclose(mine[k], expected[k]) for k in ("ixx", "iyy", "izz"))
    print(f"{name}: {'✓' if ok else '✗'} {mine}  (attendu {expected})")
    return ok
""",
    "en": """
def compare(name, mine):
    expected = reference.link(name).inertial.inertia
    if mine is None:
        print(f"{name}: no answer yet")
        return False
    ok = all(np.isclose(mine[k], expected[k]) for k in ("ixx", "iyy", "izz"))
    print(f"{name}: {'✓' if ok else '✗'} {mine}  (expected {expected})")
    return ok
""",
}


def _setup(lang: str, solution: bool = False) -> str:
    """The first code cell; the solution's leaves out what only the validator part needs."""
    imports = _IMPORTS.strip("\n")
    if solution:
        imports = imports.replace("import re\nfrom pathlib import Path\n\n", "")
        imports = imports.replace("\nfrom bras_kit.validate import validate", "")
    blocks = [imports + "\n\n" + _LANGUAGE[lang] + "\n" + _REFERENCE[lang]]
    if not solution:
        blocks.append(_SHOW[lang].strip("\n"))
    blocks.append(_COMPARE[lang].strip("\n"))
    return "\n\n\n".join(blocks)


SETUP = code(_setup("fr"), _setup("en"))
SOLUTION_SETUP = code(_setup("fr", solution=True), _setup("en", solution=True))

CHECK = code(
    """
    results = [
        compare("bras", box_inertia(1.0, 0.08, 0.08, 0.6)),
        compare("avant_bras", box_inertia(0.5, 0.06, 0.06, 0.5)),
        compare("base", cylinder_inertia(2.0, 0.15, 0.1)),
    ]
    """
)

LESSON.cells = [
    INTRO,
    SETUP,
    md(
        """
        ## Exercice

        Complétez les deux fonctions ci-dessous (elles renvoient `None` tant qu'elles ne sont pas
        écrites). La cellule suivante les compare aux valeurs du modèle pour les trois segments :
        le bras (1 kg, 0,08 × 0,08 × 0,6 m), l'avant-bras (0,5 kg, 0,06 × 0,06 × 0,5 m) et la base
        (cylindre de 2 kg, r = 0,15 m, h = 0,1 m). La solution est dans
        `solutions/07-solution-inerties.ipynb`.
        """,
        """
        ## Exercise

        Complete the two functions below (they return `None` until written). The next cell
        compares them with the template's values for the three links: the upper arm (1 kg,
        0.08 × 0.08 × 0.6 m), the forearm (0.5 kg, 0.06 × 0.06 × 0.5 m) and the base (2 kg
        cylinder, r = 0.15 m, h = 0.1 m). The solution is in `solutions/07-solution-inertials.ipynb`.
        """,
    ),
    code(
        """
        def box_inertia(m, x, y, z):
            # à compléter : renvoyer {"ixx": ..., "iyy": ..., "izz": ...}
            return None


        def cylinder_inertia(m, r, h):
            # à compléter
            return None
        """,
        """
        def box_inertia(m, x, y, z):
            # to do: return {"ixx": ..., "iyy": ..., "izz": ...}
            return None


        def cylinder_inertia(m, r, h):
            # to do
            return None
        """,
    ),
    CHECK,
    md(
        """
        ## Le centre de masse

        La forme du bras est centrée à mi-longueur (`z = 0.3`), le centre de masse aussi : l'
        `origin` de `<inertial>` n'est pas celle de l'articulation. Le modèle avec `inertials=True` :
        """,
        """
        ## The centre of mass

        The upper arm's shape is centred half-way up (`z = 0.3`), and so is its centre of mass: the
        `<inertial>`'s `origin` is not the joint's. The template with `inertials=True`:
        """,
    ),
    code(
        """
        for link in reference.links:
            inertial = link.inertial
            print(f"{link.name:11s} m={inertial.mass:<4} centre={inertial.origin.xyz}")
        show(validate(reference, lang="@LANG@"))
        """
    ),
    md(
        """
        (L'info BK506 est un détail à connaître : `robot_state_publisher` ignore l'inertie du segment
        racine et le signale par un avertissement au démarrage.)

        ## Une mauvaise inertie

        Les trois moments d'un vrai corps vérifient l'**inégalité triangulaire** :
        `ixx + iyy ≥ izz` (et de même pour les autres paires). Un nombre tapé de travers la
        brise facilement ; Gazebo refuse alors le modèle ou le fait exploser. Mettons
        `izz = 0.1` au bras (au lieu de 0,00107) :
        """,
        """
        (The BK506 note is a detail worth knowing: `robot_state_publisher` ignores the root link's
        inertia and says so with a warning at start-up.)

        ## A bad inertia

        The three moments of a real body obey the **triangle inequality**: `ixx + iyy ≥ izz` (and
        likewise for the other pairs). One mistyped number easily breaks it; Gazebo then rejects
        the model or makes it blow up. Give the upper arm `izz = 0.1` (instead of 0.00107):
        """,
    ),
    code(
        """
        good = bras_kit.arm_urdf(inertials=True)
        start = good.index('<link name="bras">')
        end = good.index("</link>", start)
        block = good[start:end]
        bad_block = re.sub(r'izz="[^"]*"', 'izz="0.1"', block)
        Path("inertie_fausse.urdf").write_text(good[:start] + bad_block + good[end:], encoding="utf-8")
        bad = bras_kit.load("inertie_fausse.urdf")
        print(bad.link("bras").inertial.inertia)
        show(validate(bad, lang="@LANG@"))
        """
    ),
    md(
        """
        Deux autres fautes classiques : une masse nulle ou négative, et un segment sans `<inertial>`
        dans un modèle qui en a ailleurs (Gazebo l'ignore ou le fusionne avec son parent).
        """,
        """
        Two other classic mistakes: a zero or negative mass, and a link with no `<inertial>` in a
        model that has them elsewhere (Gazebo ignores it or merges it into its parent).
        """,
    ),
    code(
        """
        zero_mass = good[:start] + re.sub(r'<mass value="[^"]*"', '<mass value="0"', block) + good[end:]
        Path("masse_nulle.urdf").write_text(zero_mass, encoding="utf-8")
        show(validate(bras_kit.load("masse_nulle.urdf"), lang="@LANG@"))
        print()
        no_inertial = good[:start] + re.sub(r"<inertial>.*?</inertial>", "", block, flags=re.S) + good[end:]
        Path("sans_inertie.urdf").write_text(no_inertial, encoding="utf-8")
        show(validate(bras_kit.load("sans_inertie.urdf"), lang="@LANG@"))
        """
    ),
    md(
        """
        ## Ce qu'un simulateur en fait : le couple à l'épaule

        Avec les masses et les centres de masse, on peut calculer ce que RViz ne dira jamais :
        le couple que le moteur de l'épaule doit fournir pour **tenir** le bras contre la
        gravité. Chaque segment pèse `m·g` en son centre de masse ; le couple autour de l'axe y de
        l'épaule est la somme des bras de levier.
        """,
        """
        ## What a simulator does with them: the shoulder torque

        With masses and centres of mass, we can work out what RViz will never tell: the torque the
        shoulder motor must give to **hold** the arm against gravity. Each link weighs `m·g` at its
        centre of mass; the torque about the shoulder's y axis is the sum of the lever arms.
        """,
    ),
    code(
        """
        tree = bras_kit.tf_tree(reference)


        def shoulder_torque(pose, g=9.81):
            poses = bras_kit.fk(tree, pose)
            shoulder = poses["bras"][:3, 3]
            torque = 0.0
            for name in ("bras", "avant_bras"):
                inertial = reference.link(name).inertial
                centre = (poses[name] @ [*inertial.origin.xyz, 1])[:3]
                lever = centre - shoulder
                weight = np.array([0, 0, -inertial.mass * g])
                torque += np.cross(lever, weight)[1]  # autour de y
            return torque


        effort = reference.joint("epaule").limit.effort
        for epaule in (0.0, 0.5, 1.0, 1.57):
            print(f"epaule={epaule:4.2f}  couple={shoulder_torque({'epaule': epaule}):+6.2f} N·m  (effort max {effort})")
        """,
        """
        tree = bras_kit.tf_tree(reference)


        def shoulder_torque(pose, g=9.81):
            poses = bras_kit.fk(tree, pose)
            shoulder = poses["bras"][:3, 3]
            torque = 0.0
            for name in ("bras", "avant_bras"):
                inertial = reference.link(name).inertial
                centre = (poses[name] @ [*inertial.origin.xyz, 1])[:3]
                lever = centre - shoulder
                weight = np.array([0, 0, -inertial.mass * g])
                torque += np.cross(lever, weight)[1]  # about y
            return torque


        effort = reference.joint("epaule").limit.effort
        for epaule in (0.0, 0.5, 1.0, 1.57):
            print(f"epaule={epaule:4.2f}  torque={shoulder_torque({'epaule': epaule}):+6.2f} N·m  (max effort {effort})")
        """,
    ),
    md(
        """
        Bras à l'horizontale, il faut environ 7,1 N·m : `9.81 × (1 × 0.3 + 0.5 × 0.85)`. C'est
        sous l'effort maximal de 10 N·m de l'URDF, mais avec un avant-bras deux fois plus lourd,
        le moteur ne tiendrait plus. Un simulateur physique ferait ce calcul à chaque pas de temps.
        """,
        """
        Arm horizontal, it takes about 7.1 N·m: `9.81 × (1 × 0.3 + 0.5 × 0.85)`. That is under the
        URDF's maximum effort of 10 N·m, but with a forearm twice as heavy the motor could no
        longer hold it. A physics simulator does this sum at every time step.
        """,
    ),
]

SOLUTION.cells = [
    INTRO,
    SOLUTION_SETUP,
    code(
        """
        def box_inertia(m, x, y, z):
            return {"ixx": m / 12 * (y**2 + z**2), "iyy": m / 12 * (x**2 + z**2), "izz": m / 12 * (x**2 + y**2)}


        def cylinder_inertia(m, r, h):
            side = m / 12 * (3 * r**2 + h**2)
            return {"ixx": side, "iyy": side, "izz": m * r**2 / 2}
        """
    ),
    CHECK,
    code(
        """
        assert all(results)
        print(box_inertia(1.0, 0.08, 0.08, 0.6))  # ixx = iyy = 0.030533, izz = 0.0010667
        """
    ),
    md(
        """
        Pourquoi `ixx` du bras est-il trente fois `izz` ? Le bras est long et fin : tourner
        autour de sa longueur (z) ne déplace presque pas de matière, basculer autour de x ou y en
        déplace beaucoup, loin de l'axe.
        """,
        """
        Why is the upper arm's `ixx` thirty times its `izz`? The arm is long and thin: spinning
        about its length (z) barely moves any matter, tipping about x or y moves a lot of it, far
        from the axis.
        """,
    ),
]
