"""Lesson 10: xacro properties, macros and args; the project's own template."""

from ._cells import Lesson, code, md

LESSON = Lesson(
    "10",
    {"fr": "xacro", "en": "xacro"},
    {"fr": "10 · xacro : écrire l'URDF sans se répéter", "en": "10 · xacro: URDF without repeating yourself"},
)

LESSON.cells = [
    md(
        """
        L'URDF du tutoriel répète des nombres : `0.6` est la longueur du bras **et** l'origine du
        coude **et** deux fois la hauteur du centre de la boîte. Changez-en un, oubliez l'autre, et
        les segments ne se touchent plus. **xacro** est une surcouche de l'URDF qui ajoute trois
        outils :

        | outil | s'écrit | rôle |
        |---|---|---|
        | propriété | `<xacro:property name="L" value="0.6"/>` puis `${L}` | nommer un nombre, calculer avec |
        | macro | `<xacro:macro name="m" params="a b">…</xacro:macro>` | un bloc réutilisable |
        | argument | `<xacro:arg name="x" default="…"/>` puis `$(arg x)` | une valeur donnée de l'extérieur (`x:=…`) |

        `xacro` lit ce fichier et écrit un URDF ordinaire. `bras_kit.expand_xacro` utilise le vrai
        paquet xacro, sans ROS.
        """,
        """
        The tutorial's URDF repeats numbers: `0.6` is the upper arm's length **and** the elbow's
        origin **and** twice the height of the box's centre. Change one, forget another, and the
        segments no longer meet. **xacro** is a layer over URDF that adds three tools:

        | tool | written | purpose |
        |---|---|---|
        | property | `<xacro:property name="L" value="0.6"/>` then `${L}` | name a number, compute with it |
        | macro | `<xacro:macro name="m" params="a b">…</xacro:macro>` | a reusable block |
        | argument | `<xacro:arg name="x" default="…"/>` then `$(arg x)` | a value given from outside (`x:=…`) |

        `xacro` reads such a file and writes plain URDF. `bras_kit.expand_xacro` uses the real xacro
        package, without ROS.
        """,
    ),
    code(
        """
        from pathlib import Path

        import bras_kit

        bras_kit.set_language("@LANG@")  # the library's messages and picture words in this notebook's language
        small = '''<?xml version="1.0"?>
        <robot name="deux_blocs" xmlns:xacro="http://www.ros.org/wiki/xacro">
          <xacro:arg name="hauteur" default="0.4"/>
          <xacro:property name="h" value="$(arg hauteur)"/>

          <xacro:macro name="bloc" params="name h">
            <link name="${name}">
              <visual>
                <origin xyz="0 0 ${h / 2}"/>
                <geometry><box size="0.1 0.1 ${h}"/></geometry>
              </visual>
            </link>
          </xacro:macro>

          <xacro:bloc name="socle" h="0.1"/>
          <xacro:bloc name="colonne" h="${h}"/>

          <joint name="pivot" type="revolute">
            <parent link="socle"/>
            <child link="colonne"/>
            <origin xyz="0 0 0.1"/>
            <axis xyz="0 0 1"/>
            <limit lower="-3.14" upper="3.14" effort="5" velocity="1"/>
          </joint>
        </robot>
        '''
        Path("deux_blocs.urdf.xacro").write_text(small, encoding="utf-8")
        print(bras_kit.expand_xacro("deux_blocs.urdf.xacro"))
        """
    ),
    md(
        """
        La macro `bloc` a produit deux segments ; `${h / 2}` a été calculé. Donnons maintenant une
        autre valeur à l'argument, comme `xacro fichier hauteur:=1.0` en ligne de commande :
        """,
        """
        The `bloc` macro produced two links; `${h / 2}` was computed. Now give the argument
        another value, like `xacro file hauteur:=1.0` on the command line:
        """,
    ),
    code(
        """
        tall = bras_kit.load("deux_blocs.urdf.xacro", mappings={"hauteur": "1.0"})
        colonne = tall.link("colonne").visuals[0]
        print(colonne.geometry.size, colonne.origin.xyz)
        """
    ),
    md(
        """
        ## Le modèle du projet

        Le bras de `bras_kit` vient lui-même d'un fichier xacro livré avec le paquet. Ses
        arguments sont les paramètres de la leçon 1 ; deux drapeaux (`wrist`, `inertials`)
        ajoutent le poignet et les inerties des exercices. Regardons ses deux macros principales :
        """,
        """
        ## The project's own template

        `bras_kit`'s arm itself comes from a xacro file shipped with the package. Its arguments
        are the parameters of lesson 1; two flags (`wrist`, `inertials`) add the wrist and the
        inertials of the exercises. Let us look at its two main macros:
        """,
    ),
    code(
        """
        from bras_kit.core.resources import robot_template

        template = robot_template().read_text(encoding="utf-8")
        print(robot_template().name, "-", len(template.splitlines()), "lignes")


        def show_block(text, start, end):
            lines = text.splitlines()
            first = next(i for i, line in enumerate(lines) if start in line)
            last = next(i for i in range(first, len(lines)) if end in lines[i])
            print("\\n".join(lines[first:last + 1]), end="\\n\\n")


        show_block(template, '<xacro:macro name="segment"', "</xacro:macro>")
        show_block(template, '<xacro:macro name="revolute"', "</xacro:macro>")
        """,
        """
        from bras_kit.core.resources import robot_template

        template = robot_template().read_text(encoding="utf-8")
        print(robot_template().name, "-", len(template.splitlines()), "lines")


        def show_block(text, start, end):
            lines = text.splitlines()
            first = next(i for i, line in enumerate(lines) if start in line)
            last = next(i for i in range(first, len(lines)) if end in lines[i])
            print("\\n".join(lines[first:last + 1]), end="\\n\\n")


        show_block(template, '<xacro:macro name="segment"', "</xacro:macro>")
        show_block(template, '<xacro:macro name="revolute"', "</xacro:macro>")
        """,
    ),
    md(
        """
        Deux idées à retenir :

        * `segment` place la boîte à `length / 2` : la pièce **commence** à l'origine de son segment
          et monte le long de z, quelle que soit sa longueur ;
        * l'articulation qui suit est appelée avec `z="${bras_length}"` : l'origine du coude **est** la
          longueur du bras. Les deux ne peuvent plus se contredire (voir la leçon 8, où on les
          désaccorde exprès).

        Et les butées : `$(arg ${name}_lower)` fabrique le nom de l'argument à partir du nom de
        l'articulation. Les appels en bas du fichier :
        """,
        """
        Two ideas to keep:

        * `segment` places the box at `length / 2`: the piece **starts** at its link's origin and
          runs up z, whatever its length;
        * the following joint is called with `z="${bras_length}"`: the elbow's origin **is** the
          upper arm's length. The two can no longer disagree (see lesson 8, where we break them
          on purpose).

        And the limits: `$(arg ${name}_lower)` builds the argument's name from the joint's name.
        The calls at the bottom of the file:
        """,
    ),
    code(
        """
        show_block(template, '<xacro:segment name="bras"', "/>")
        show_block(template, '<xacro:revolute name="coude"', "/>")
        show_block(template, '<xacro:if value="$(arg wrist)">', "</xacro:if>")
        """
    ),
    md(
        """
        Développer ce modèle avec des arguments, c'est ce que fait `bras_kit.arm(...)` :
        """,
        """
        Expanding the template with arguments is what `bras_kit.arm(...)` does:
        """,
    ),
    code(
        """
        by_xacro = bras_kit.load(robot_template(), mappings={"bras_length": "0.8", "wrist": "true"})
        by_arm = bras_kit.arm(params={"bras_length": 0.8}, wrist=True)
        for name in ("coude", "poignet"):
            print(name, by_xacro.joint(name).origin.xyz, by_arm.joint(name).origin.xyz)
        """
    ),
    md(
        """
        ## Ce que xacro n'a pas le droit de faire ici

        Une expression `${...}` de xacro est du Python. Un fichier venu d'ailleurs pourrait donc
        cacher du code ; `bras_kit` refuse tout ce qui n'est pas un calcul :
        """,
        """
        ## What xacro may not do here

        A xacro `${...}` expression is Python. A file from elsewhere could therefore hide code;
        `bras_kit` refuses anything that is not arithmetic:
        """,
    ),
    code(
        """
        Path("piege.urdf.xacro").write_text(
            '<robot name="piege" xmlns:xacro="http://www.ros.org/wiki/xacro">'
            '<link name="${__import__(\\'os\\').getcwd()}"/></robot>', encoding="utf-8")
        try:
            bras_kit.expand_xacro("piege.urdf.xacro")
        except bras_kit.BrasKitError as error:
            print(type(error).__name__, ":", bras_kit.say(error))
        """
    ),
    md(
        """
        ## À vous

        Dans `deux_blocs.urdf.xacro`, ajoutez un troisième bloc `tete` de 0,1 m posé sur la
        colonne, avec une articulation fixe dont l'origine est `${h}`. Développez avec `hauteur:=0.7` et
        vérifiez que l'origine de l'articulation suit.
        """,
        """
        ## Your turn

        In `deux_blocs.urdf.xacro`, add a third block `tete` 0.1 m high on top of the column, with
        a fixed joint whose origin is `${h}`. Expand with `hauteur:=0.7` and check the joint's
        origin follows.
        """,
    ),
    code(
        """
        head = '''
          <xacro:bloc name="tete" h="0.1"/>
          <joint name="cou" type="fixed">
            <parent link="colonne"/>
            <child link="tete"/>
            <origin xyz="0 0 ${h}"/>
          </joint>
        </robot>'''
        Path("trois_blocs.urdf.xacro").write_text(small.replace("</robot>", head), encoding="utf-8")
        three = bras_kit.load("trois_blocs.urdf.xacro", mappings={"hauteur": "0.7"})
        print(three.joint("cou").origin.xyz)
        """
    ),
]
