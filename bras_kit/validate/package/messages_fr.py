"""Libellés français des règles de paquet (BK6xx) ; fusionnés dans ``messages_fr.RULE_TEXTS``."""

from __future__ import annotations

from ..i18n import RuleText as T

RULE_TEXTS: dict[str, T] = {
    "BK600": T(
        title="un fichier du paquet est illisible",
        message={
            "missing": "{file} manque : ce n'est pas un paquet ament_python complet",
            "": "{file} est illisible : {detail}",
        },
        hint={
            "missing": "lancez 'bras-kit new' pour voir un paquet complet, ou ajoutez le fichier manquant",
            "": "corrigez cette ligne ; les vérifications qui ont besoin de ce fichier ont été sautées",
        },
        explanation="""\
Les vérifications du paquet lisent `package.xml` (en XML), `setup.py`, les fichiers de
lancement et les nœuds Python (comme source Python, sans jamais les exécuter) et les fichiers
`.rviz` (en YAML). Un fichier absent ou impossible à analyser est signalé ici, et les
vérifications qui en dépendent se taisent : corrigez-le d'abord. colcon et `ros2 launch`
échoueraient sur le même fichier.""",
    ),
    "BK601": T(
        title="un dossier dont le lancement a besoin n'est pas installé par setup.py",
        message={
            "all": "setup.py n'installe pas {folder}/ ({files}) : 'ros2 launch' dira file not found",
            "some": "setup.py n'installe pas {files} de {folder}/ : 'ros2 launch' ne les trouvera pas",
            "": "setup.py n'installe pas {files} de {folder}/",
        },
        hint="ajoutez {entry} à data_files, puis relancez colcon build",
        explanation="""\
colcon ne copie dans `install/PKG/share/PKG/` que ce que liste `data_files` dans `setup.py`.
C'est là, et non dans le dossier source, que le fichier de lancement cherche l'URDF (et qu'il
est lui-même trouvé). Un paquet qui oublie `urdf/` ou `launch/` se compile sans un mot puis
échoue au `ros2 launch` avec « file not found » : le troisième piège du tutoriel. Chaque
dossier demande sa propre entrée, puis une nouvelle compilation.""",
    ),
    "BK602": T(
        title="le fichier de lancement ouvre un fichier non installé",
        message={
            "exists": "ouvre share/{package}/{path} : {path} existe mais setup.py ne l'installe pas",
            "other": "ouvre share/{package}/{path}, mais setup.py n'installe que {installed} dans {folder}/",
            "": "ouvre share/{package}/{path}, qu'aucun fichier du paquet n'installe",
        },
        hint={
            "exists": "ajoutez {path} à data_files dans setup.py, puis relancez colcon build",
            "other": "utilisez un des noms installés ({installed}), ou installez {path}",
            "": "corrigez le nom du fichier, ou ajoutez le fichier au paquet et à data_files",
        },
        explanation="""\
Le fichier de lancement construit des chemins dans le dossier share installé
(`get_package_share_directory`, `FindPackageShare`) et les ouvre, ou les passe à un nœud (le
`-d` de RViz). Ce chemin doit désigner un fichier que `setup.py` installe à cet endroit, avec
le même dossier et le même nom ; sinon le lancement échoue avec « file not found » (ou RViz
s'ouvre sans configuration). Un URDF renommé ou une faute de frappe en sont la cause habituelle.""",
    ),
    "BK603": T(
        title="le paquet n'est pas enregistré dans l'index ament",
        message={
            "file": "{marker} manque : ros2 ne trouvera pas le paquet {package} une fois installé",
            "entry": "data_files n'installe pas {marker} dans share/ament_index/resource_index/packages : "
                     "ros2 ne trouvera pas le paquet {package}",
            "": "le paquet {package} n'est pas enregistré dans l'index ament ({marker})",
        },
        hint={
            "file": "créez le fichier vide {marker}",
            "": "ajoutez ('share/ament_index/resource_index/packages', ['{marker}']) à data_files",
        },
        explanation="""\
`ros2 launch`, `ros2 run` et `get_package_share_directory` trouvent les paquets installés par
l'index ament : un fichier vide au nom du paquet, installé dans
`share/ament_index/resource_index/packages`. `ros2 pkg create` crée `resource/PKG` et l'entrée
de `data_files` ; en supprimer un donne « package not found » alors que la compilation a réussi.""",
    ),
    "BK604": T(
        title="les noms de package.xml et de setup.py diffèrent",
        message="package.xml nomme le paquet '{xml_name}' mais setup.py (ligne {setup_line}) le nomme '{setup_name}'",
        hint="gardez un seul nom partout : <name> de package.xml, package_name de setup.py, resource/NOM",
        explanation="""\
colcon connaît le paquet par le `<name>` de `package.xml` ; setuptools l'installe sous le nom
donné dans `setup.py`, et le fichier de lancement cherche son dossier share par son nom. S'ils
diffèrent, les fichiers sont installés dans un dossier et cherchés dans un autre : « package not
found » ou « file not found » au lancement. Renommer un paquet, c'est changer tous ces noms.""",
    ),
    "BK605": T(
        title="un paquet que démarre le fichier de lancement n'est pas déclaré dans package.xml",
        message="le fichier de lancement {launch} (ligne {launch_line}) démarre un nœud de '{dependency}', "
                "que package.xml ne déclare pas en <exec_depend>",
        hint="ajoutez <exec_depend>{dependency}</exec_depend> à package.xml",
        explanation="""\
`rosdep install` installe ce que déclare `package.xml`. Un nœud démarré par le fichier de
lancement mais non déclaré marche sur la machine où il se trouve déjà installé, et échoue
ailleurs avec « package not found ». Chaque paquet dont le lancement démarre un nœud
(robot_state_publisher, joint_state_publisher_gui, rviz2...) doit figurer en `<exec_depend>`.""",
    ),
    "BK606": T(
        title="adresse e-mail du mainteneur invalide dans package.xml",
        message={
            "none": "package.xml n'a pas de <maintainer>",
            "missing": "le mainteneur '{maintainer}' n'a pas d'attribut email",
            "": "le mainteneur '{maintainer}' a une adresse invalide '{email}' : colcon ne verra pas un paquet ROS",
        },
        hint={
            "none": 'ajoutez <maintainer email="vous@exemple.fr">Votre Nom</maintainer>',
            "": 'écrivez une vraie adresse : <maintainer email="vous@exemple.fr">',
        },
        explanation="""\
colcon lit `package.xml` avec catkin_pkg, qui refuse un mainteneur sans adresse e-mail valide
(nom@domaine.tld). colcon ignore alors le manifeste, compile le dossier comme un simple paquet
Python et n'installe jamais le marqueur de l'index ament : `ros2 launch` ne trouve pas le
paquet alors que la compilation semblait réussie. Un « TODO » laissé en adresse en est la cause
habituelle.""",
    ),
    "BK610": T(
        title="le Fixed Frame de RViz n'est pas un link du robot",
        message={
            "missing": "la configuration RViz ne fixe aucun Fixed Frame : RViz prend 'map', que ce robot ne publie pas",
            "": "le Fixed Frame '{frame}' n'est pas un link du robot ({links}) : RViz n'affiche rien",
        },
        hint="réglez Fixed Frame sur '{root}' (Global Options > Fixed Frame)",
        explanation="""\
RViz dessine tout par rapport à son Fixed Frame. Quand aucun repère TF ne porte ce nom (le
`map` par défaut, ou un link renommé), RViz affiche « Frame does not exist » et une vue vide :
le premier piège du tutoriel. Prenez le link racine du robot, `base` dans le tutoriel.""",
    ),
    "BK611": T(
        title="la configuration RViz n'affiche pas le modèle du robot",
        message={
            "missing": "la configuration RViz n'a pas d'affichage RobotModel : le bras n'est pas dessiné",
            "disabled": "l'affichage RobotModel est désactivé : le bras n'est pas dessiné",
            "topic": "RobotModel lit sa description sur '{topic}', et non sur /robot_description",
            "": "l'affichage RobotModel n'est pas configuré",
        },
        hint={
            "missing": "ajoutez un affichage RobotModel avec Description Topic /robot_description, "
                       "puis enregistrez la configuration",
            "disabled": "cochez l'affichage RobotModel (Enabled: true) et enregistrez la configuration",
            "": "réglez Description Topic sur /robot_description",
        },
        explanation="""\
robot_state_publisher publie l'URDF sur le topic `/robot_description`. L'affichage RobotModel
de RViz ne dessine les links que s'il lit ce topic ; avec un autre topic, ou sans RobotModel,
RViz reste vide alors que tout tourne : le premier piège du tutoriel.""",
    ),
    "BK612": T(
        title="la configuration RViz n'a pas d'affichage TF",
        message="pas d'affichage TF : les repères des links ne sont pas montrés",
        hint="ajoutez un affichage TF (Add > TF) pour voir le repère de chaque link, puis enregistrez la configuration",
        explanation="""\
L'affichage TF dessine le repère et le nom de chaque link : c'est ainsi que le tutoriel montre
ce que calcule robot_state_publisher. Le modèle du robot apparaît quand même sans lui : c'est
un conseil, pas un défaut.""",
    ),
    "BK613": T(
        title="RViz est démarré sans configuration",
        message={
            "unused": "rviz2 est démarré sans -d, {config} n'est donc pas utilisé : RViz s'ouvre vide",
            "": "rviz2 est démarré sans configuration : RViz s'ouvre vide",
        },
        hint={
            "unused": "passez arguments=['-d', os.path.join(get_package_share_directory('{package}'), '{config}')]",
            "": "enregistrez une configuration dans rviz/{package}.rviz, installez-la et passez-la avec arguments=['-d', ...]",
        },
        explanation="""\
Démarré sans `-d`, RViz ouvre sa configuration par défaut : Fixed Frame `map`, pas de modèle
de robot. Le tutoriel règle alors le Fixed Frame et ajoute RobotModel à la main, à chaque
lancement. Enregistrer cette configuration dans le paquet, l'installer et la passer avec `-d`
montre le bras tout de suite.""",
    ),
    "BK620": T(
        title="rien ne publie sur /joint_states",
        message={
            "nodes": "le fichier de lancement démarre robot_state_publisher mais rien qui publie sur /joint_states "
                     "({node} le ferait, mais n'est pas démarré) : les articulations {joints} n'ont pas d'angle",
            "": "le fichier de lancement démarre robot_state_publisher mais rien qui publie sur /joint_states : "
                "les articulations {joints} n'ont pas d'angle",
        },
        hint="démarrez joint_state_publisher_gui (ou votre nœud d'animation) dans le fichier de lancement",
        explanation="""\
robot_state_publisher calcule les repères des links mobiles à partir des angles reçus sur
`/joint_states`. Sans publieur, ces links n'ont pas de transformation : RViz les montre à
l'origine ou pas du tout, et rien ne bouge. C'est le deuxième piège du tutoriel ;
joint_state_publisher_gui ou un nœud d'animation doit tourner.""",
    ),
    "BK621": T(
        title="un nœud publie des noms JointState qui ne sont pas les articulations du robot",
        message={
            "unknown": "JointState nomme {names}, qui ne sont pas des articulations mobiles du robot ({joints})",
            "missing": "JointState ne nomme jamais {names} (il nomme {published}) : ces articulations ne bougent pas",
            "": "les noms JointState ne correspondent pas aux articulations mobiles du robot",
        },
        hint={
            "unknown": "utilisez les noms d'articulations de l'URDF : {joints}",
            "missing": "ajoutez {names} aux noms, avec une position pour chacun",
            "": "nommez chaque articulation mobile de l'URDF",
        },
        explanation="""\
robot_state_publisher associe les entrées de JointState à l'URDF par leur nom. Un nom que le
robot n'a pas est ignoré ; une articulation mobile jamais nommée n'a pas de transformation, et
son link enfant et tout ce qui suit ne bougent pas (ou disparaissent de RViz). La cause
habituelle : une articulation ajoutée à l'URDF, comme le `poignet` du tutoriel, mais pas au
`msg.name` du nœud.""",
    ),
    "BK622": T(
        title="un nœud n'a pas de point d'entrée console_scripts",
        message={
            "launch": "le fichier de lancement démarre '{executable}' de {package}, mais setup.py ne "
                      "déclare aucune entrée console_scripts de ce nom",
            "node": "{node_file} publie JointState et a un main(), mais aucune entrée console_scripts ne le lance",
            "module": "l'entrée console_scripts '{executable}' désigne {module}, qui n'existe pas",
            "function": "l'entrée console_scripts '{executable}' désigne {module}:{function}, qui n'est pas définie",
            "": "un nœud n'a pas de point d'entrée console_scripts",
        },
        hint={
            "launch": "ajoutez {entry} à entry_points['console_scripts'] dans setup.py",
            "node": "ajoutez {entry} à entry_points['console_scripts'] dans setup.py",
            "": "faites pointer l'entrée vers un module et une fonction existants (module.chemin:main)",
        },
        explanation="""\
`ros2 run PKG NOM` et le `Node(package=PKG, executable=NOM)` d'un fichier de lancement
exécutent les programmes que `setup.py` déclare dans `entry_points['console_scripts']`
(`'NOM = PKG.module:main'`). Un nœud sans entrée n'est jamais installé comme programme :
« No executable found », et le robot ne bouge pas.""",
    ),
    "BK623": T(
        title="le mouvement d'un nœud sort des butées",
        message={
            "upper": "l'articulation '{joint}' suit {formula} : au-dessus de sa butée haute {bound} "
                     "dès t = {time} s, jusqu'à {value} {unit}",
            "lower": "l'articulation '{joint}' suit {formula} : au-dessous de sa butée basse {bound} "
                     "dès t = {time} s, jusqu'à {value} {unit}",
            "": "l'articulation '{joint}' suit {formula}, qui sort de ses butées",
        },
        hint="réduisez l'amplitude pour rester entre lower et upper, ou élargissez les limites de l'URDF",
        explanation="""\
Quand un nœud écrit ses positions sous forme de formules littérales (`0.8 * math.sin(t)`),
bras-kit suit chacune pendant une minute avec les mêmes vérifications de butées que
`--motion` et la compare au `<limit>` de l'articulation. robot_state_publisher dessine ce qu'il
reçoit : le bras dépasse ses butées dans RViz, et un vrai robot ou un simulateur le refuserait.
C'est le cinquième piège du tutoriel. Les formules non littérales (lues dans des paramètres,
calculées ailleurs) ne sont pas jugées.""",
    ),
}

# BK640-BK651 : ce qu'une exécution du nœud a montré (bras-kit run, validate --run)
RULE_TEXTS.update({
    "BK640": T(
        title="le nœud a levé une exception à l'exécution",
        message="le nœud a levé {kind} à t = {time} s de temps simulé : {detail}",
        hint="la trace ci-dessus montre votre fichier et votre ligne ; ros2 run arrêterait le nœud au même endroit",
        explanation="""\
`bras-kit run` a exécuté le `main()` du nœud avec sa doublure de rclpy, et le code du nœud a
levé une exception. La doublure vérifie ce que vérifie le vrai rclpy : un champ de message du
mauvais type (une liste d'entiers pour `position`, un flottant pour `name`) échoue comme
l'affirment les classes de messages générées ; un Node créé avant `rclpy.init()`, ou un spin
après `destroy_node()`, échoue comme avec rclpy. La trace ne garde que vos fichiers, et le
temps simulé indique à quel tic.""",
    ),
    "BK641": T(
        title="le nœud utilise une partie de ROS 2 que bras-kit ne simule pas",
        message="le nœud utilise {what} (à t = {time} s), que bras-kit run ne simule pas",
        hint="lancez-le avec ros2 run sur une machine ROS 2, la vraie référence ; bras-kit run couvre les bases "
             "de rclpy (nœuds, publishers, abonnements, timers, rates, paramètres, journaux) et les messages courants",
        explanation="""\
La doublure couvre ce qu'utilisent le nœud du tutoriel et les nœuds de débutant :
`rclpy.init/spin/spin_once/shutdown`, `Node` avec publishers, abonnements, timers, rates,
paramètres, horloge et journal, les profils QoS, et les messages de sensor_msgs (JointState),
std_msgs, builtin_interfaces et geometry_msgs. Services, actions, tf2, launch et les autres
paquets de messages ne sont pas simulés : l'exécution s'arrête là plutôt que de faire semblant.""",
    ),
    "BK642": T(
        title="le nœud publie dans une boucle où le temps ne passe pas",
        message="le nœud a publié des milliers de messages sur {topics} sans que le temps avance "
                "(arrêté à t = {time} s)",
        hint="publiez depuis un timer (create_timer) et faites tourner le nœud (spin), ou dormez dans la boucle "
             "(time.sleep(0.05))",
        explanation="""\
Une boucle `while` qui publie sans jamais dormir, tourner (spin) ni attendre envoie des messages
aussi vite que le processeur le permet : des centaines de milliers par seconde sur une vraie
machine, un déluge pour robot_state_publisher et RViz, et un cœur du processeur à 100 %.
L'horloge de bras-kit n'avance jamais dans une telle boucle : l'exécution l'arrête après dix
mille messages au même instant.""",
    ),
    "BK643": T(
        title="rate.sleep() sans exécuteur qui tourne : un vrai nœud resterait bloqué",
        message="le nœud a appelé rate.sleep() {count} fois sans exécuteur qui tourne dans un autre fil",
        hint="utilisez create_timer et rclpy.spin, ou faites tourner le nœud dans un fil avant la boucle",
        explanation="""\
Dans rclpy, `Rate.sleep()` attend un timer qu'un exécuteur doit faire tourner, dans un autre
fil d'exécution (rclpy/timer.py). Un nœud qui l'appelle dans sa boucle principale sans spin
ailleurs reste bloqué pour toujours à son premier sommeil sous `ros2 run`. L'horloge simulée de
bras-kit laisse la boucle continuer pour vérifier le reste, et le signale ici.""",
    ),
    "BK644": T(
        title="rien n'a été publié sur /joint_states",
        message={
            "other": "rien n'a été publié sur /joint_states ; les messages JointState sont allés sur {topics} "
                     "({count} messages) : robot_state_publisher n'écoute pas ce sujet",
            "type": "/joint_states a transporté {types}, pas sensor_msgs/msg/JointState",
            "silent": "le nœud a créé un publisher JointState sur {topic} mais n'y a jamais publié "
                      "en {time} s",
            "": "rien n'a été publié sur /joint_states en {time} s (sujets publiés : {topics})",
        },
        hint={
            "other": "créez le publisher sur 'joint_states' (ou '/joint_states'), le sujet auquel "
                     "robot_state_publisher s'abonne",
            "type": "publiez des messages sensor_msgs.msg.JointState sur /joint_states",
            "silent": "appelez publish(msg) à chaque tic (dans le callback du timer), et faites tourner le nœud",
            "": "créez un publisher JointState sur 'joint_states' et publiez depuis un timer",
        },
        explanation="""\
robot_state_publisher prend les angles des articulations sur `/joint_states` et nulle part
ailleurs. Un nœud qui publie sur `joint_state` ou `/bras/joint_states` reste du ROS valide (ces
noms de sujet sont légaux) mais personne ne l'écoute : le robot apparaît et ne bouge pas, le
deuxième piège du tutoriel. Ne rien publier du tout (pas de timer, pas de spin, `publish`
oublié) donne le même symptôme.""",
    ),
    "BK645": T(
        title="listes name et position JointState de longueurs différentes",
        message="un JointState nomme {names} articulations mais donne {positions} positions (t = {time} s ; "
                "{count} messages de ce genre)",
        hint="donnez une position par nom, dans le même ordre",
        explanation="""\
robot_state_publisher associe `name[i]` à `position[i]`. Quand les deux listes n'ont pas la même
longueur, il rejette le message entier avec une erreur (« has 2 joint names but 3 positions ») :
le bras ne bouge plus du tout, même pour les articulations correctes.""",
    ),
    "BK646": T(
        title="le nœud nomme des articulations que le robot n'a pas",
        message="le JointState du nœud nomme {names}, qui ne sont pas des articulations mobiles du robot ({joints})",
        hint="utilisez les noms d'articulations de l'URDF : {joints}",
        explanation="""\
robot_state_publisher associe les entrées du JointState à l'URDF par leur nom et ignore les
autres. Un nom mal orthographié (`Coude`, `elbow`, `coude_joint`) laisse donc l'articulation sans
angle, alors que le nœud tourne sans erreur. L'exécution montre les noms réellement envoyés.""",
    ),
    "BK647": T(
        title="des articulations mobiles que le nœud ne nomme jamais",
        message="le JointState du nœud ne nomme jamais {names} (il nomme {published}) : ces articulations "
                "ne bougent pas",
        hint="ajoutez {names} à msg.name, avec une position pour chacune",
        explanation="""\
Une articulation mobile qui n'apparaît jamais sur `/joint_states` n'a pas de transformation :
robot_state_publisher ne peut pas placer son lien enfant, que RViz montre alors à l'origine ou
pas du tout. La cause habituelle : une articulation ajoutée à l'URDF (le `poignet` du tutoriel)
mais pas au message du nœud.""",
    ),
    "BK648": T(
        title="une position qui n'est pas un nombre",
        message="l'articulation '{joint}' a reçu la position {value} à t = {time} s",
        hint="vérifiez le calcul (une division par zéro, math.inf, un NaN lu sur un capteur)",
        explanation="""\
Un message JointState accepte NaN et l'infini (les classes générées ne vérifient que le type),
mais aucune transformation ne peut en être tirée : robot_state_publisher publie des repères
absurdes et RViz n'affiche rien ou avertit. L'exécution signale la première valeur de ce genre
pour chaque articulation.""",
    ),
    "BK649": T(
        title="des positions publiées au-delà des butées",
        message={
            "upper": "l'articulation '{joint}' a reçu {value} {unit} à t = {time} s, au-dessus de sa butée haute "
                     "{bound} ({count} messages au-delà, le premier à t = {first} s)",
            "lower": "l'articulation '{joint}' a reçu {value} {unit} à t = {time} s, au-dessous de sa butée basse "
                     "{bound} ({count} messages au-delà, le premier à t = {first} s)",
            "degrees": "l'articulation '{joint}' a reçu {value} à t = {time} s, au-delà de sa butée {bound} : "
                       "on dirait des degrés ({count} messages, le premier à t = {first} s)",
        },
        hint={
            "upper": "gardez les positions entre les butées lower et upper de l'URDF (en radians)",
            "lower": "gardez les positions entre les butées lower et upper de l'URDF (en radians)",
            "degrees": "les positions JointState sont en radians : convertissez avec math.radians()",
        },
        explanation="""\
robot_state_publisher dessine tout ce qu'il reçoit : au-delà d'un `<limit>`, le bras traverse
ses propres butées dans RViz, et un vrai robot ou un simulateur refuserait la commande. C'est le
cinquième piège du tutoriel, vu dans les messages que le nœud a réellement envoyés (des degrés
au lieu de radians en sont la cause la plus fréquente).""",
    ),
    "BK650": T(
        title="header.stamp laissé à zéro",
        message="{count} messages JointState sur {total} ont un header.stamp à zéro",
        hint="écrivez msg.header.stamp = self.get_clock().now().to_msg() avant de publier",
        explanation="""\
robot_state_publisher horodate les repères qu'il publie avec le temps du JointState. Un
horodatage nul (1er janvier 1970) donne des transformations vieilles de plus de cinquante ans :
RViz et tf2 refusent de les utiliser (« extrapolation into the past ») ou les utilisent en
retard. Le nœud du tutoriel horodate chaque message avec l'horloge du nœud pour cette raison.""",
    ),
    "BK651": T(
        title="fréquence de publication loin de celle du timer",
        message="/joint_states a été publié à {rate} Hz, mais le timer de {period} s demande {expected} Hz",
        hint="publiez une fois par appel du timer (pas dans une boucle à l'intérieur, pas seulement de temps en temps)",
        explanation="""\
Un nœud avec un seul timer qui publie une fois par tic envoie ses messages à la fréquence du
timer (20 Hz pour les 0,05 s du tutoriel). Une fréquence très différente signifie que le
callback publie plusieurs fois, ou seulement de temps en temps, ou qu'une autre boucle publie :
le mouvement dans RViz saccade ou s'emballe.""",
    ),
})
