"""Lesson 3: render the arm, sliders like joint_state_publisher_gui, RViz's settings."""

from ._cells import Lesson, code, md

LESSON = Lesson(
    "03",
    {"fr": "le-voir", "en": "see-it"},
    {"fr": "3 · Le voir : rendu et curseurs", "en": "3 · See it: pictures and sliders"},
)

LESSON.cells = [
    md(
        """
        Dans le tutoriel, RViz dessine le bras et une petite fenêtre à curseurs
        (`joint_state_publisher_gui`) fixe l'angle de chaque articulation. Ici, `bras_kit.render` dessine
        le bras hors écran (une image = un tableau numpy) et des curseurs `ipywidgets` jouent le
        rôle de la fenêtre.
        """,
        """
        In the tutorial, RViz draws the arm and a small slider window (`joint_state_publisher_gui`)
        sets each joint's angle. Here `bras_kit.render` draws the arm off-screen (a picture is a
        numpy array) and `ipywidgets` sliders play the part of the window.
        """,
    ),
    code(
        """
        import matplotlib.pyplot as plt

        import bras_kit
        from bras_kit.render import render_pose

        bras_kit.set_language("@LANG@")  # the library's messages and picture words in this notebook's language
        robot = bras_kit.arm()
        image = render_pose(robot, {"epaule": 0.4, "coude": 0.9}, size=(480, 360))
        print(image.shape, image.dtype)
        plt.imshow(image)
        plt.axis("off")
        plt.show()
        """
    ),
    md(
        """
        ## Quelques poses côte à côte

        Les butées sont `epaule ∈ [-1.57, 1.57]` et `coude ∈ [-2, 2]`. `tf=True` ajoute les
        trièdres des repères, comme l'affichage TF de RViz (x rouge, y vert, z bleu).
        """,
        """
        ## A few poses side by side

        The limits are `epaule ∈ [-1.57, 1.57]` and `coude ∈ [-2, 2]`. `tf=True` adds the frame
        axes, like RViz's TF display (x red, y green, z blue).
        """,
    ),
    code(
        """
        poses = [{}, {"epaule": 0.8}, {"epaule": -0.5, "coude": 1.5}, {"epaule": 1.2, "coude": -2.0}]
        fig, axes = plt.subplots(1, len(poses), figsize=(14, 4))
        for ax, pose in zip(axes, poses):
            ax.imshow(render_pose(robot, pose, size=(320, 320), tf=True))
            ax.set_title(", ".join(f"{k}={v}" for k, v in pose.items()) or "zéro")
            ax.axis("off")
        plt.show()
        """,
        """
        poses = [{}, {"epaule": 0.8}, {"epaule": -0.5, "coude": 1.5}, {"epaule": 1.2, "coude": -2.0}]
        fig, axes = plt.subplots(1, len(poses), figsize=(14, 4))
        for ax, pose in zip(axes, poses):
            ax.imshow(render_pose(robot, pose, size=(320, 320), tf=True))
            ax.set_title(", ".join(f"{k}={v}" for k, v in pose.items()) or "zero")
            ax.axis("off")
        plt.show()
        """,
    ),
    md(
        """
        ## Des curseurs, comme joint_state_publisher_gui

        Un curseur par articulation mobile, borné par ses butées : c'est exactement ce que fait la fenêtre
        du tutoriel, qui lit les `limit` de l'URDF. Bougez un curseur, l'image est redessinée.

        L'image suit le curseur pendant que vous le faites glisser (`continuous_update=True`) : une
        seule image, remplacée sur place, sans empiler de nouvelles images sous le panneau. Le
        glissement envoie bien plus de valeurs que le rendu ne sait en dessiner : on dessine au plus
        30 fois par seconde, et toujours la dernière valeur.
        """,
        """
        ## Sliders, like joint_state_publisher_gui

        One slider per movable joint, bounded by its limits: exactly what the tutorial's window
        does, reading the URDF's `limit` elements. Move a slider and the picture is redrawn.

        The picture follows the slider while you drag it (`continuous_update=True`): one picture,
        replaced in place, with no pile of pictures under the panel. Dragging sends many more
        values than the renderer can draw: it draws at most 30 times a second, and always the
        last value.
        """,
    ),
    code(
        """
        import asyncio
        import io
        import time

        import ipywidgets as widgets
        from IPython.display import display

        from bras_kit.render import Renderer, save_png, show_image

        # Un seul moteur de rendu pour tous les dessins ; sa caméra cadre toutes les poses permises,
        # si bien que la vue ne bouge pas quand les curseurs bougent.
        renderer = Renderer(robot, size=(480, 360), tf=True)
        screen = widgets.Image(format="png")  # une seule image, remplacée sur place à chaque dessin
        sliders = {joint.name: widgets.FloatSlider(value=0.0, min=joint.bounds()[0], max=joint.bounds()[1], step=0.01,
                                                   description=joint.name, continuous_update=True)
                   for joint in robot.movable_joints()}
        FRAME = 1 / 30  # s : pas plus d'un dessin par trentième de seconde
        drawn = {"at": 0.0, "later": None}


        def draw():
            \"""Dessine la pose des curseurs dans l'image du panneau.\"""
            drawn["later"] = None
            buffer = io.BytesIO()
            save_png(renderer.render({name: slider.value for name, slider in sliders.items()}), buffer)
            screen.value = buffer.getvalue()
            drawn["at"] = time.monotonic()


        def on_slide(change):
            wait = FRAME - (time.monotonic() - drawn["at"])
            if drawn["later"] is not None:
                return  # un dessin est déjà prévu : il lira les dernières valeurs
            if wait <= 0:
                draw()
            else:  # trop tôt : dessiner les dernières valeurs dès que le délai est passé
                drawn["later"] = asyncio.get_running_loop().call_later(wait, draw)


        for slider in sliders.values():
            slider.observe(on_slide, names="value")
        draw()
        display(widgets.VBox([screen, *sliders.values()]))

        picture = renderer.render({"epaule": 0.6, "coude": -1.1})  # l'image de ces valeurs, calculée sans l'afficher
        """,
        """
        import asyncio
        import io
        import time

        import ipywidgets as widgets
        from IPython.display import display

        from bras_kit.render import Renderer, save_png, show_image

        # One renderer for every redraw; its camera frames all the poses the limits allow,
        # so the view stays put while the sliders move.
        renderer = Renderer(robot, size=(480, 360), tf=True)
        screen = widgets.Image(format="png")  # one picture, replaced in place at each redraw
        sliders = {joint.name: widgets.FloatSlider(value=0.0, min=joint.bounds()[0], max=joint.bounds()[1], step=0.01,
                                                   description=joint.name, continuous_update=True)
                   for joint in robot.movable_joints()}
        FRAME = 1 / 30  # s: no more than one drawing per thirtieth of a second
        drawn = {"at": 0.0, "later": None}


        def draw():
            \"""Draw the sliders' pose into the panel's picture.\"""
            drawn["later"] = None
            buffer = io.BytesIO()
            save_png(renderer.render({name: slider.value for name, slider in sliders.items()}), buffer)
            screen.value = buffer.getvalue()
            drawn["at"] = time.monotonic()


        def on_slide(change):
            wait = FRAME - (time.monotonic() - drawn["at"])
            if drawn["later"] is not None:
                return  # a drawing is already due: it will read the latest values
            if wait <= 0:
                draw()
            else:  # too soon: draw the latest values as soon as the delay is over
                drawn["later"] = asyncio.get_running_loop().call_later(wait, draw)


        for slider in sliders.values():
            slider.observe(on_slide, names="value")
        draw()
        display(widgets.VBox([screen, *sliders.values()]))

        picture = renderer.render({"epaule": 0.6, "coude": -1.1})  # the picture of these values, computed without showing it
        """,
    ),
    md(
        """
        ## RViz dans le navigateur

        `bras_kit.view` ouvre la même chose en 3D, en direct : une page servie par votre
        ordinateur (adresse 127.0.0.1), avec un curseur par articulation, les repères TF et leurs
        noms, le choix du repère fixe, et la position de l'extrémité. Dans un Jupyter lancé sur
        votre machine, la page s'affiche sous la cellule ; ailleurs, ouvrez l'adresse affichée.
        Depuis un terminal, c'est `bras-kit view`.
        """,
        """
        ## RViz in the browser

        `bras_kit.view` opens the same thing in 3D, live: a page served by your computer
        (address 127.0.0.1), one slider per joint, the TF frames with their names, the Fixed Frame
        to choose, and the position of the tip. In a Jupyter running on your machine the page
        shows under the cell; elsewhere, open the address printed. From a terminal it is
        `bras-kit view`.
        """,
    ),
    code(
        """
        viewer = bras_kit.view(robot, port=0, motion="tutorial", lang="@LANG@")
        print(viewer.url)
        """
    ),
    code(
        """
        viewer.stop()  # run this cell when you are done with the 3D view
        """
    ),
    md(
        """
        ## Les deux réglages de RViz qui comptent

        Le tutoriel demande deux réglages dans RViz ; sans eux, la fenêtre reste vide.

        * **Fixed Frame = `base`.** RViz dessine tout dans un repère choisi. Il doit exister dans
          l'arbre TF : c'est la racine de notre arbre, le seul repère qui ne bouge pas. Un nom qui
          n'existe pas (`map`, `base_link`…) et RViz ne sait où placer aucun segment.
        * **RobotModel → Description Topic = `/robot_description`.** L'affichage RobotModel a
          besoin de la forme des segments ; `robot_state_publisher` publie l'URDF sur ce topic. Sans
          lui, RViz connaît les repères mais pas les pièces à dessiner.

        `render_pose` fait les deux choses d'un coup : il prend l'URDF directement (pas de topic)
        et dessine dans le repère de la racine.
        """,
        """
        ## The two RViz settings that matter

        The tutorial asks for two settings in RViz; without them the window stays empty.

        * **Fixed Frame = `base`.** RViz draws everything in one chosen frame. It must exist in the
          TF tree: it is our tree's root, the only frame that never moves. Give a name that does
          not exist (`map`, `base_link`…) and RViz cannot place any link.
        * **RobotModel → Description Topic = `/robot_description`.** The RobotModel display needs
          the links' shapes; `robot_state_publisher` publishes the URDF on that topic. Without it
          RViz knows the frames but not the pieces to draw.

        `render_pose` does both at once: it takes the URDF directly (no topic) and draws in the
        root's frame.
        """,
    ),
    code(
        """
        tree = bras_kit.tf_tree(robot)
        print("Fixed Frame à choisir :", tree.root)
        print("repères publiés      :", tree.links)
        print("'base_link' existe ? ", "base_link" in tree.links)
        """,
        """
        tree = bras_kit.tf_tree(robot)
        print("Fixed Frame to choose:", tree.root)
        print("frames published:     ", tree.links)
        print("does 'base_link' exist?", "base_link" in tree.links)
        """,
    ),
    md(
        """
        ## À vous

        Rendez le bras vu de face (`view="front"`) : c'est la vue où le mouvement, dans le plan
        x-z, se lit le mieux. Quels autres points de vue `render_pose` propose-t-il ?
        """,
        """
        ## Your turn

        Draw the arm seen from the front (`view="front"`): motion happens in the x-z plane, so this
        is the view that shows it best. Which other viewpoints does `render_pose` offer?
        """,
    ),
    code(
        """
        from bras_kit.render import VIEWS

        print(list(VIEWS))
        display(show_image(render_pose(robot, {"epaule": 0.6, "coude": -1.1}, size=(480, 360), view="front")))
        """
    ),
]
