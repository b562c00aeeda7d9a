"""Textes français de chaque règle : titre, message, correctif, explication (``bras-kit explain CODE``)."""

from __future__ import annotations

from .i18n import RuleText as T

UI = {
    "error": "erreur",
    "warning": "avertissement",
    "info": "info",
    "hint": "correctif",
    "checked_one": "{n} fichier vérifié",
    "checked_many": "{n} fichiers vérifiés",
    "unreadable_one": "{n} illisible",
    "unreadable_many": "{n} illisibles",
    "errors_one": "{n} erreur",
    "errors_many": "{n} erreurs",
    "warnings_one": "{n} avertissement",
    "warnings_many": "{n} avertissements",
    "infos_one": "{n} info",
    "infos_many": "{n} infos",
    "colon": " : ",
    "clean": "aucun problème",
    "family": "Famille",
    "message": "Message",
    "fix": "Correctif",
    "skip": "Pour l'ignorer : bras-kit validate --ignore {code}",
    "family_structure": "structure (est-ce un robot, et un seul arbre ?)",
    "family_joints": "articulations (types, axes, limites)",
    "family_pitfalls": "pièges du tutoriel",
    "family_geometry": "géométrie (formes, maillages, couleurs)",
    "family_inertia": "inertie (masse et inertie pour la simulation)",
    "family_package": "le paquet ROS 2 (setup.py, fichier de lancement, configuration RViz, nœuds)",
}

RULE_TEXTS: dict[str, T] = {
    # ------------------------------------------------------------------ BK1xx structure
    "BK100": T(
        title="le fichier n'est pas du XML bien formé",
        message={"": "XML mal formé : {detail}", "encoding": "le fichier n'est pas du texte UTF-8 : l'octet {byte} de la ligne {at} serait '{guess}' en Latin-1, le fichier a donc sans doute été enregistré en Latin-1 ou Windows-1252"},
        hint={"": "regardez cette ligne : une balise non fermée, un '/>' oublié ou un guillemet en trop sont les causes habituelles", "encoding": 'réenregistrez le fichier en UTF-8 dans votre éditeur (ou déclarez son encodage : <?xml version="1.0" encoding="ISO-8859-1"?>)'},
        explanation="""\
Le fichier ne peut pas être lu comme du XML, donc rien d'autre n'y a été vérifié. La ligne
indiquée est celle où le lecteur XML s'est arrêté ; l'erreur est souvent sur cette ligne ou
juste au-dessus : une balise jamais fermée, un `<box size="...">` écrit sans son `/`, un
guillemet ouvert et jamais refermé, ou un `&` qu'il faut écrire `&amp;`.

C'est un échec de lecture : `bras-kit validate` le signale comme un constat (pour que l'éditeur
et la CI voient la ligne) et se termine avec le code 2, comme pour toute entrée illisible.""",
    ),
    "BK101": T(
        title="XML dangereux refusé (DTD ou entité)",
        message={
            "dtd": "refusé : le fichier déclare une DTD (<!DOCTYPE ...>){where}",
            "entity": "refusé : le fichier déclare une entité (<!ENTITY ...>){where}",
            "external": "refusé : le fichier fait référence à une entité externe{where}",
            "undefined": "refusé : le fichier utilise une référence d'entité (&nom;) que bras-kit ne développe pas{where}",
            "": "refusé : le fichier utilise une DTD ou une entité{where}",
        },
        hint={
            "undefined": "écrivez le caractère lui-même au lieu de la référence &nom;",
            "": "supprimez le bloc <!DOCTYPE ...> : un fichier URDF n'en a jamais besoin",
        },
        explanation="""\
Une DTD ou une déclaration d'entité permet à un fichier XML d'aller lire d'autres fichiers, ou
de transformer quelques octets en plusieurs gigaoctets (« billion laughs »). L'URDF n'en a
jamais besoin : bras-kit refuse ces fichiers avant de lire quoi que ce soit vers quoi ils
pointent. Aucun fichier n'est ouvert, aucune adresse n'est contactée.

Supprimez le bloc `<!DOCTYPE ...>` et écrivez le texte en clair au lieu des références
`&nom;`. Comme toute entrée illisible, ce constat fait sortir `bras-kit validate` avec le
code 2.""",
    ),
    "BK102": T(
        title="xacro n'a pas pu développer le fichier",
        message="échec de xacro : {detail}",
        hint={
            "arg": "donnez l'argument en ligne de commande (--xacro-arg nom:=valeur) ou une valeur par défaut dans <xacro:arg>",
            "property": "définissez la propriété avec <xacro:property name=... value=...> avant de l'utiliser",
            "include": "vérifiez le chemin du fichier inclus : un chemin relatif part du fichier qui l'inclut",
            "package": "indiquez où se trouve le paquet : --package-path DOSSIER ou BRAS_KIT_PACKAGE_PATH",
            "unsafe": "une expression xacro ne peut que calculer des nombres et des textes à partir des propriétés",
            "xml": "regardez cette ligne : une balise non fermée ou un guillemet en trop",
            "": "vérifiez la syntaxe xacro autour de cette ligne",
        },
        explanation="""\
Un fichier `.xacro` est développé avec le vrai paquet xacro avant d'être vérifié. Quand le
développement échoue (propriété ou argument non défini, fichier inclus introuvable,
`$(find paquet)` vers un paquet inconnu, expression que bras-kit refuse d'évaluer), rien
d'autre ne peut être vérifié.

`$(find paquet)` cherche dans les dossiers donnés par `--package-path` et
`BRAS_KIT_PACKAGE_PATH`, puis dans les variables de ROS. Les expressions qui pourraient
exécuter du code (imports, noms à double soulignement, puissances énormes) sont refusées.
Ce constat fait sortir `bras-kit validate` avec le code 2.""",
    ),
    "BK103": T(
        title="le fichier ne peut pas être lu",
        message={
            "missing": "fichier introuvable : {path}",
            "folder": "{path} est un dossier, pas un fichier",
            "": "impossible de lire {path} : {detail}",
        },
        hint={
            "missing": "vérifiez le chemin et son orthographe",
            "folder": "donnez le dossier lui-même à bras-kit validate : il vérifie les fichiers .urdf et .xacro qu'il contient",
            "": "vérifiez que le fichier existe et que vous avez le droit de le lire",
        },
        explanation="""\
Le chemin donné à `bras-kit validate` n'existe pas, n'est pas lisible, ou désigne un dossier à
la place d'un fichier. Les autres chemins de la même commande sont tout de même vérifiés ; la
commande se termine ensuite avec le code 2 pour que les scripts le remarquent.""",
    ),
    "BK125": T(
        title="la déclaration <?xml ?> n'est pas tout au début du fichier",
        message='la déclaration <?xml ...?> est à la ligne {at}, après des lignes vides ou des espaces : les lecteurs XML stricts refusent le fichier',
        hint='supprimez les lignes vides et les espaces avant <?xml',
        explanation="""\
XML n'autorise rien, pas même une ligne vide, avant la déclaration `<?xml version="1.0"?>`.
urdfdom (`check_urdf`, robot_state_publisher) et pybullet lisent quand même un tel fichier :
bras-kit le lit donc aussi et vérifie le reste ; mais des outils plus stricts (les lecteurs XML
de Python, certains éditeurs et convertisseurs) le refusent. Supprimez ce qui précède `<?xml`.""",
    ),
    "BK126": T(
        title='un URDF généré depuis un fichier xacro voisin',
        message='cet URDF a été généré depuis {xacro}, qui est vérifié à sa place ; les deux concordent',
        hint='modifiez {xacro} et régénérez ce fichier plutôt que de le retoucher à la main',
        explanation="""\
Un paquet ROS 2 contient souvent `bras.urdf.xacro` et le `bras.urdf` qui en est tiré. Quand
`bras-kit validate` trouve les deux dans un dossier, il ne vérifie que le fichier xacro (chaque
constat une seule fois, à la ligne à corriger) et compare l'URDF au développement du xacro.""",
    ),
    "BK127": T(
        title='un URDF généré ne correspond plus à son fichier xacro',
        message="cet URDF diffère de ce que donne maintenant {xacro} ({difference}) : il n'est plus à jour",
        hint='régénérez-le : bras-kit xacro {xacro} -o {urdf} --force',
        explanation="""\
Quand un dossier contient `bras.urdf.xacro` et `bras.urdf`, l'URDF est considéré comme généré
depuis le xacro. S'ils divergent, le paquet installe et lance le fichier que nomme le fichier de
lancement : RViz peut alors montrer un robot plus ancien que celui que vous avez modifié.
Régénérez l'URDF (ou faites lancer xacro par le fichier de lancement).""",
    ),
    "BK124": T(
        title="fichier xacro ne contenant que des macros",
        message="ce fichier xacro définit des macros mais aucun link : c'est une bibliothèque, vérifiée à travers les fichiers qui l'incluent",
        hint="vérifiez le fichier .xacro principal qui inclut celui-ci",
        explanation="""\
Les paquets de description ROS séparent souvent un robot en un fichier principal
`robot.urdf.xacro` et des fichiers annexes qui ne définissent que des blocs `<xacro:macro>`.
Développé seul, un fichier annexe donne un robot sans link, ce qui serait une erreur (BK106)
pour un vrai fichier de robot. Quand un `.xacro` ne donne aucun link et définit des macros,
bras-kit affiche cette remarque à la place et n'y vérifie rien d'autre.""",
    ),
    "BK104": T(
        title="l'élément racine n'est pas <robot>",
        message="l'élément racine est <{tag}>, pas <robot>",
        hint='un fichier URDF a un seul élément racine, <robot name="...">, qui contient ses links et ses articulations',
        explanation="""\
Tout fichier URDF a un unique élément racine, `<robot name="...">` ; robot_state_publisher et
RViz refusent tout le reste. Cela arrive quand on donne un extrait d'un fichier plus grand (un
`<link>` seul) ou un fichier SDF (`<sdf>`) au lieu d'un URDF.""",
    ),
    "BK105": T(
        title="le robot n'a pas de nom",
        message="<robot> n'a pas d'attribut name",
        hint='nommez le robot : <robot name="bras">',
        explanation="""\
L'attribut `name` de `<robot>` est obligatoire : l'analyseur URDF de ROS s'arrête sur « No
name given for the robot » et robot_state_publisher ne publie jamais rien. N'importe quel nom
convient.""",
    ),
    "BK106": T(
        title="le robot n'a aucun link",
        message="le robot n'a aucun <link>",
        hint='ajoutez au moins un link, par exemple <link name="base"/>',
        explanation="""\
Un robot est fait de links (les pièces rigides) reliés par des articulations. Sans aucun
`<link>`, il n'y a rien à publier ni à afficher. Si ce fichier est une bibliothèque de macros
xacro, vérifiez plutôt le fichier qui l'inclut.""",
    ),
    "BK107": T(
        title="deux links portent le même nom",
        message="le link '{link}' est défini deux fois (la première fois ligne {first_line})",
        hint="renommez l'un des deux : les noms de links doivent être uniques, et les articulations les désignent par leur nom",
        explanation="""\
Les articulations désignent les links par leur nom, et TF publie un repère par nom de link :
chaque nom ne peut servir qu'une fois. L'analyseur de ROS refuse un fichier où un nom de link
se répète. La cause habituelle : copier un link pour créer un nouveau segment (l'exercice du
poignet) en oubliant de le renommer.""",
    ),
    "BK108": T(
        title="deux articulations portent le même nom",
        message="l'articulation '{joint}' est définie deux fois (la première fois ligne {first_line})",
        hint="renommez l'une des deux : les noms d'articulations doivent être uniques (ce sont les noms de /joint_states)",
        explanation="""\
Les noms d'articulations servent de clés dans les messages `/joint_states` et nomment les
curseurs de joint_state_publisher_gui : chacun doit être unique. L'analyseur de ROS refuse un
nom d'articulation répété. Un link et une articulation peuvent porter le même nom (le
`poignet` du tutoriel), mais pas deux articulations.""",
    ),
    "BK109": T(
        title="un matériau de premier niveau est défini deux fois",
        message="le matériau '{material}' est défini deux fois au premier niveau (la première fois ligne {first_line})",
        hint="gardez un seul <material name=\"{material}\"> en tête de fichier, ou renommez le second",
        explanation="""\
Les matériaux déclarés directement sous `<robot>` sont partagés par leur nom. Déclarer deux
fois le même nom à cet endroit fait échouer l'analyseur URDF de ROS (« material is not
unique ») : le robot n'est pas chargé.""",
    ),
    "BK110": T(
        title="un même nom de matériau reçoit deux couleurs",
        message="le matériau '{material}' du link '{link}' a la couleur {colour}, mais '{material}' vaut déjà {first_colour} (ligne {first_line}), et c'est cette définition qui l'emporte",
        hint="donnez à ce matériau un nom à lui, ou la même couleur aux deux endroits",
        explanation="""\
Les matériaux sont partagés par leur nom : la première définition d'un nom (celles de premier
niveau d'abord) s'applique à tous les visuels qui l'utilisent. Un `<material name="x">` plus
loin avec une autre couleur est ignoré sans prévenir, et un segment s'affiche dans une couleur
inattendue. Utilisez un nom différent par couleur.""",
    ),
    "BK111": T(
        title="le link parent d'une articulation n'existe pas",
        message="l'articulation '{joint}' a pour parent le link '{link}', qui n'est pas défini",
        hint={
            "close": "vouliez-vous dire '{close}' ? Les noms de links doivent correspondre exactement, majuscules comprises",
            "": "définissez <link name=\"{link}\"> ou utilisez l'un des links : {links}",
        },
        explanation="""\
`<parent link="...">` doit désigner un link défini dans le même fichier, écrit exactement de la
même façon (majuscules, soulignés, accents). Sinon l'articulation est suspendue dans le vide :
l'analyseur de ROS échoue et robot_state_publisher ne publie rien.""",
    ),
    "BK112": T(
        title="le link enfant d'une articulation n'existe pas",
        message="l'articulation '{joint}' a pour enfant le link '{link}', qui n'est pas défini",
        hint={
            "close": "vouliez-vous dire '{close}' ? Les noms de links doivent correspondre exactement, majuscules comprises",
            "": "définissez <link name=\"{link}\"> ou utilisez l'un des links : {links}",
        },
        explanation="""\
`<child link="...">` doit désigner un link défini dans le même fichier, écrit exactement de la
même façon. Une faute de frappe ici laisse le link visé déconnecté et fait échouer l'analyseur
de ROS.""",
    ),
    "BK113": T(
        title="une articulation relie un link à lui-même",
        message="l'articulation '{joint}' a '{link}' à la fois pour parent et pour enfant",
        hint="une articulation relie deux links différents : celui auquel elle est accrochée (parent) et celui qu'elle fait bouger (enfant)",
        explanation="""\
Une articulation place un link enfant par rapport à un link parent ; relier un link à lui-même
est une boucle de longueur un, sans aucun sens. En général, la ligne de l'enfant a été copiée
depuis celle du parent sans être modifiée.""",
    ),
    "BK114": T(
        title="un link a deux parents",
        message="le link '{link}' est l'enfant de l'articulation '{first_joint}' (ligne {first_line}) et de nouveau de l'articulation '{joint}'",
        hint="chaque link est accroché à une seule articulation : changez l'enfant de '{joint}' ou supprimez-la",
        explanation="""\
L'URDF décrit un arbre : chaque link sauf la racine est l'enfant d'une et une seule
articulation. Une seconde articulation vers le même enfant rendrait sa position ambiguë ;
l'analyseur de ROS la refuse et TF ne peut pas publier le repère. Les chaînes fermées
(mécanismes parallèles) ne s'écrivent pas directement en URDF.""",
    ),
    "BK115": T(
        title="les articulations forment une boucle",
        message="les articulations forment une boucle : {loop}",
        hint="cassez la boucle : l'une des articulations {joints} remonte dans l'arbre ; donnez-lui pour enfant un nouveau link",
        explanation="""\
En remontant d'enfant en parent, on doit finir par arriver à la racine. Ici, on revient au point
de départ : aucun de ces links ne peut être placé et aucune racine ne peut leur être trouvée.
Le plus souvent, le parent et l'enfant d'une articulation ont été inversés.""",
    ),
    "BK116": T(
        title="plusieurs links racines",
        message="le robot a plusieurs links racines : {roots}",
        hint="accrochez '{extra}' sous un autre link par une articulation (par exemple une articulation fixe depuis '{root}')",
        explanation="""\
Un arbre URDF a exactement un link racine, celui qui n'est l'enfant d'aucune articulation (dans
le tutoriel, `base`, choisi comme Fixed Frame dans RViz). Avec plusieurs racines, l'analyseur de
ROS s'arrête sur « Two root links found » et rien n'est publié. Reliez chaque racine en trop par
une articulation.""",
    ),
    "BK117": T(
        title="un link n'est relié à rien",
        message="le link '{link}' n'est relié par aucune articulation",
        hint="ajoutez une articulation avec <child link=\"{link}\"/>, par exemple depuis '{root}', ou supprimez le link",
        explanation="""\
Chaque link doit être atteint depuis la racine en passant par des articulations. Un link
qu'aucune articulation ne mentionne est une seconde racine : l'analyseur de ROS refuse le
fichier, et RViz ne saurait de toute façon pas où le placer. C'est souvent un link ajouté pour
l'exercice du poignet avant que son articulation soit écrite.""",
    ),
    "BK118": T(
        title="type d'articulation inconnu",
        message="l'articulation '{joint}' est de type '{type}', que l'URDF ne connaît pas",
        hint={
            "close": 'vouliez-vous dire type="{close}" ? Les types s\'écrivent en minuscules',
            "": "utilisez l'un de ces types : {types}",
        },
        explanation="""\
L'URDF connaît six types d'articulations : `revolute` (rotation avec butées), `continuous`
(rotation sans butée), `prismatic` (translation), `fixed`, `floating` et `planar`. Les types
s'écrivent en minuscules ; tout autre mot fait échouer l'analyseur de ROS.""",
    ),
    "BK119": T(
        title="du xacro reste dans un fichier URDF",
        message={
            "more": "balisage xacro dans un URDF simple : <{tag}> (et {more} autres lignes)",
            "": "balisage xacro dans un URDF simple : <{tag}>",
        },
        hint="développez-le d'abord (bras-kit xacro {path} -o robot.urdf), ou nommez le fichier .xacro pour que bras-kit le développe",
        explanation="""\
Les éléments `<xacro:...>` et les expressions `${...}` / `$(...)` n'ont de sens que pour l'outil
xacro. Un lecteur URDF les voit comme du texte inconnu : les propriétés ne sont pas remplacées
et les nombres deviennent illisibles. Développez le fichier avec `bras-kit xacro FICHIER -o
FICHIER.urdf` (ou le `xacro` de ROS), ou donnez-lui l'extension `.xacro` pour que
`bras-kit validate` le développe avant de le vérifier.""",
    ),
    "BK120": T(
        title="une articulation mimic suit une articulation qui n'existe pas",
        message="l'articulation '{joint}' imite '{leader}', qui n'est pas une articulation de ce robot",
        hint={
            "close": "vouliez-vous dire '{close}' ?",
            "": "nommez l'une des articulations : {joints}",
        },
        explanation="""\
`<mimic joint="...">` fait recopier à une articulation la valeur d'une autre (multipliée par un
facteur, plus un décalage), comme les doigts d'une pince. Il doit désigner une autre
articulation du même robot.""",
    ),
    "BK121": T(
        title="des articulations mimic se suivent en boucle",
        message="des articulations mimic se suivent en boucle : {chain}",
        hint="une articulation de la chaîne doit être commandée directement : retirez le <mimic> de l'une d'elles",
        explanation="""\
Une articulation mimic recopie la valeur de celle qu'elle suit. Si celle-ci imite à son tour
(directement ou par d'autres) la première, aucune valeur ne peut jamais être calculée : au
moins une articulation de la chaîne doit être commandée par `/joint_states`.""",
    ),
    "BK122": T(
        title="un attribut ou un élément obligatoire manque",
        message={
            "element": "<{tag}> n'a pas de <{attribute}>",
            "": "<{tag}> n'a pas d'attribut '{attribute}'",
        },
        hint="ajoutez-le, par exemple {example}",
        explanation="""\
Certains attributs et éléments sont obligatoires en URDF : les noms des links et des
articulations, le type d'articulation, son parent et son enfant, la taille d'un pavé, le rayon
et la longueur d'un cylindre, la valeur d'une masse, les six valeurs d'inertie. Sans eux,
l'analyseur de ROS échoue ou prend une valeur par défaut qui n'a pas de sens.""",
    ),
    "BK123": T(
        title="une valeur n'est pas un nombre",
        message={
            "one": "<{tag}> {attribute}=\"{value}\" n'est pas un nombre",
            "": "<{tag}> {attribute}=\"{value}\" n'est pas une suite de {count} nombres",
        },
        hint={
            "one": "écrivez un nombre avec un point décimal, par exemple 0.6 (pas 0,6, et sans unité)",
            "": "écrivez {count} nombres séparés par des espaces, par exemple {example}",
        },
        explanation="""\
En URDF, les nombres s'écrivent avec un point décimal et sans unité (mètres, radians,
kilogrammes), et les vecteurs comme des nombres séparés par des espaces : `xyz="0 0 0.6"`.
Une virgule décimale (`0,6`), une unité (`0.6m`), une composante en trop ou en moins, ou une
expression xacro restée telle quelle rendent la valeur illisible.""",
    ),
    # ------------------------------------------------------------------ BK2xx articulations
    "BK200": T(
        title="une articulation revolute ou prismatic n'a pas de <limit>",
        message={
            "prismatic": "l'articulation prismatic '{joint}' n'a pas de <limit>",
            "": "l'articulation revolute '{joint}' n'a pas de <limit>",
        },
        hint={
            "prismatic": 'ajoutez <limit lower="0" upper="0.2" effort="100" velocity="0.5"/> (mètres, N, m/s)',
            "": 'ajoutez <limit lower="-1.57" upper="1.57" effort="10" velocity="1.0"/> (radians, N.m, rad/s), '
                'ou passez-la en type="continuous" si elle tourne sans butée',
        },
        explanation="""\
Les articulations revolute et prismatic ont des butées : l'URDF exige donc un `<limit>` avec
`lower`, `upper` (en radians ou en mètres), `effort` et `velocity`. Sans lui, l'analyseur de ROS
refuse l'articulation. Une articulation qui tourne sans butée (une roue) est `continuous` et n'a
pas besoin de limites.""",
    ),
    "BK201": T(
        title="<limit> sans effort ou sans velocity",
        message="articulation '{joint}' : il manque {missing} dans <limit>",
        hint="ajoutez {attributes} (force ou couple maximal, et vitesse maximale ; toute valeur positive convient pour RViz)",
        explanation="""\
Un `<limit>` doit donner `effort` (force ou couple maximal) et `velocity` (vitesse maximale) :
sinon l'analyseur de ROS échoue sur « joint limit: no effort », même si RViz ne s'en sert
jamais. Seuls `lower` et `upper` ont une valeur par défaut (0).""",
    ),
    "BK202": T(
        title="limite basse au-dessus de la limite haute",
        message="articulation '{joint}' : la limite basse {lower} est au-dessus de la limite haute {upper} {unit}",
        hint='inversez-les : lower="{upper}" upper="{lower}"',
        explanation="""\
L'articulation ne peut bouger qu'entre `lower` et `upper` ; si `lower` est au-dessus de
`upper`, aucune position n'est permise. joint_state_publisher_gui affiche un curseur
inutilisable et les contrôleurs refusent de bouger l'articulation. Les deux valeurs ont
sans doute été inversées, ou un signe s'est perdu.""",
    ),
    "BK203": T(
        title="l'articulation ne peut pas bouger (lower == upper)",
        message={
            "unwritten": "articulation '{joint}' : <limit> ne donne ni lower ni upper, les deux valent donc 0 et l'articulation ne peut pas bouger",
            "": "articulation '{joint}' : lower et upper valent tous deux {value} {unit}, l'articulation ne peut donc pas bouger",
        },
        hint={
            "unwritten": 'ajoutez la plage, par exemple lower="-1.57" upper="1.57"',
            "": 'donnez une plage (lower < upper), ou passez l\'articulation en type="fixed" si elle ne doit pas bouger',
        },
        explanation="""\
Quand `lower` est égal à `upper`, la seule position permise est cette valeur : le curseur ne
bouge pas. `lower` et `upper` valent 0 quand ils ne sont pas écrits, et c'est la façon habituelle
d'en arriver là. Si l'articulation ne doit vraiment pas bouger, une articulation `fixed` le dit
clairement.""",
    ),
    "BK204": T(
        title="l'axe de l'articulation est nul",
        message="articulation '{joint}' : <axis xyz=\"0 0 0\"> n'a pas de direction",
        hint='donnez la direction de rotation ou de translation, par exemple <axis xyz="0 1 0"/>',
        explanation="""\
L'axe est la direction autour de laquelle tourne une articulation revolute, ou le long de
laquelle glisse une articulation prismatic. Un vecteur nul n'a pas de direction : on ne peut pas
le normaliser et le mouvement n'est pas défini (KDL et les simulateurs produisent des positions
NaN).""",
    ),
    "BK205": T(
        title="l'axe de l'articulation n'est pas unitaire",
        message="articulation '{joint}' : l'axe {axis} a pour longueur {norm} ; il sera normalisé en {unit}",
        hint='écrivez le vecteur unitaire : <axis xyz="{unit}"/>',
        explanation="""\
Les lecteurs URDF divisent l'axe par sa longueur : `0 2 0` se comporte comme `0 1 0`. Le
fichier fonctionne, mais qui le lit peut croire que la longueur compte (un rapport de
réduction, une vitesse). Écrire le vecteur unitaire évite la confusion.""",
    ),
    "BK206": T(
        title="l'axe de l'articulation est illisible",
        message={
            "missing": "articulation '{joint}' : <axis> n'a pas d'attribut xyz",
            "": "articulation '{joint}' : <axis xyz=\"{value}\"> n'est pas une suite de trois nombres",
        },
        hint='écrivez trois nombres, par exemple <axis xyz="0 1 0"/> (les articulations du tutoriel tournent autour de y)',
        explanation="""\
`<axis xyz="x y z">` demande exactement trois nombres séparés par des espaces. Un axe illisible
fait tourner l'articulation autour d'une direction par défaut (x), probablement pas celle
voulue.""",
    ),
    "BK207": T(
        title="un nombre est infini ou n'est pas un nombre",
        message="<{tag}> {attribute}=\"{value}\" n'est pas un nombre fini",
        hint="écrivez un nombre fini : inf et nan ne placent les links nulle part",
        explanation="""\
`inf`, `-inf` et `nan` passent pour des nombres auprès de certains analyseurs, mais rendent
absurde toute transformation qui les utilise : le link et tout ce qui en dépend disparaît ou
s'envole. Une articulation sans butée s'écrit `continuous`, pas avec des limites infinies.""",
    ),
    "BK208": T(
        title="une articulation continuous a des limites lower/upper",
        message="l'articulation '{joint}' est continuous : les lecteurs URDF ignorent {attributes} dans son <limit>",
        hint='passez-la en type="revolute" si elle doit s\'arrêter à ces valeurs, sinon retirez lower/upper',
        explanation="""\
Une articulation `continuous` tourne sans butée ; les lecteurs URDF ignorent `lower` et
`upper` sur elle. Si ces limites sont voulues, l'articulation est `revolute`.""",
    ),
    "BK209": T(
        title="limite d'effort ou de vitesse nulle ou négative",
        message={
            "effort": "articulation '{joint}' : la limite d'effort {value} n'est pas positive",
            "velocity": "articulation '{joint}' : la limite de vitesse {value} n'est pas positive",
        },
        hint={
            "effort": 'donnez la force ou le couple maximal que l\'articulation peut fournir, par exemple effort="10"',
            "velocity": 'donnez la vitesse maximale, par exemple velocity="1.0"',
        },
        explanation="""\
`effort` et `velocity` sont des maximums : un maximum nul ou négatif empêche l'articulation de
bouger dès qu'un contrôleur ou un simulateur applique les limites. RViz les ignore, si bien que
l'erreur passe inaperçue jusqu'à la simulation.""",
    ),
    "BK210": T(
        title="course prismatic invraisemblable",
        message="l'articulation prismatic '{joint}' parcourt {travel} m ({lower} à {upper}) ; les limites sont en mètres",
        hint='si vous avez écrit des millimètres : lower="{lower_m}" upper="{upper_m}"',
        explanation="""\
Les longueurs URDF sont en mètres. Une articulation prismatic qui parcourt plus de 10 m est rare
sur un bras ; les limites ont probablement été écrites en millimètres ou en centimètres.""",
    ),
    "BK211": T(
        title="des limites revolute qui ressemblent à des degrés",
        message="articulation '{joint}' : les limites {lower}..{upper} dépassent un tour complet ; les angles URDF sont en radians",
        hint='en radians : lower="{lower_rad}" upper="{upper_rad}"',
        explanation="""\
Les angles d'un URDF sont en radians : un quart de tour vaut 1.5708, pas 90. De vraies
articulations tournent parfois plus d'un tour (une patte d'ANYmal ±3π, le dernier axe d'un
ABB IRB 140 ±400°, écrit 6.98 rad) : bras-kit ne parle donc de degrés que pour des limites
au-delà de deux tours (12.57), ou au-delà d'un tour (6.283) quand les deux sont des nombres
entiers (±90, ±180) : des radians aussi grands ne sont jamais ronds.""",
    ),
    "BK212": T(
        title="une articulation fixe a un axe ou des limites",
        message={
            "axis": "l'articulation '{joint}' est fixe : son <axis> est ignoré",
            "limit": "l'articulation '{joint}' est fixe : son <limit> est ignoré",
            "both": "l'articulation '{joint}' est fixe : son <axis> et son <limit> sont ignorés",
        },
        hint='si elle doit bouger, donnez-lui un type mobile (type="revolute") ; sinon retirez ces éléments',
        explanation="""\
Une articulation `fixed` ne bouge jamais : son axe et ses limites sont ignorés. Les trouver là
signifie en général que le type devait être `revolute` (l'articulation n'a alors pas de curseur
dans joint_state_publisher_gui), ou que l'articulation a été copiée depuis une articulation
mobile.""",
    ),
    "BK213": T(
        title="une articulation mobile n'a pas d'<axis>",
        message={
            "prismatic": "l'articulation '{joint}' n'a pas d'<axis> : elle glisse selon x (1 0 0), la valeur par défaut de l'URDF",
            "": "l'articulation '{joint}' n'a pas d'<axis> : elle tourne autour de x (1 0 0), la valeur par défaut de l'URDF",
        },
        hint='écrivez l\'axe voulu, par exemple <axis xyz="0 1 0"/>',
        explanation="""\
Sans `<axis>`, l'URDF prend `1 0 0`. C'est valide, mais un axe oublié explique souvent un bras
qui se plie de côté dans RViz ; écrire l'axe rend l'intention visible.""",
    ),
    "BK230": T(
        title="un <safety_controller> est illisible",
        message={
            "missing": "articulation '{joint}' : <safety_controller> n'a pas d'attribut {attribute}",
            "": "articulation '{joint}' : <safety_controller {attribute}=\"{value}\"> n'est pas un nombre",
        },
        hint='écrivez des nombres, par exemple <safety_controller soft_lower_limit="-1.5" soft_upper_limit="1.5" '
             'k_position="100" k_velocity="10"/>, ou retirez l\'élément',
        explanation="""\
`<safety_controller>` indique à un vrai variateur où commencer à freiner avant les butées
(`soft_lower_limit`, `soft_upper_limit`) et avec quelle force (`k_position`, et `k_velocity`,
obligatoire). urdfdom, et donc tout outil ROS, refuse le fichier entier quand l'une de ces
valeurs n'est pas un nombre : une valeur comme `None`, laissée par un script qui a écrit une
valeur Python, empêche RViz d'afficher le robot.""",
    ),
    # ------------------------------------------------------------------ BK3xx pièges
    "BK301": T(
        title="une articulation n'est pas au bout du segment parent",
        message={
            "short": "l'articulation '{joint}' est en {coord}, mais le {tag} du link '{link}' occupe {span} : "
                     "l'enfant est accroché {distance} m avant le bout du segment",
            "beyond": "l'articulation '{joint}' est en {coord}, {distance} m après le bout du link '{link}' "
                      "(son {tag} occupe {span}) : l'enfant flotte dans le vide",
        },
        hint={
            "": "placez l'articulation au bout de '{link}' : {origin}",
        },
        explanation="""\
L'`<origin>` d'une articulation place le link enfant dans le repère du link parent. Sur un bras,
chaque articulation se trouve au bout du segment précédent : l'articulation `coude` du tutoriel
est en z = 0.6 parce que le segment `bras` mesure 0.6 m. Si l'origine ne correspond pas à la longueur du
parent, le segment suivant démarre à l'intérieur du parent ou flotte à côté (« segments mal
positionnés »).

C'est la règle pratique du tutoriel : c'est donc un avertissement, et bras-kit ne l'applique
que là où le parent ressemble aux segments du tutoriel : une articulation revolute ou continuous
dont le link parent a un seul visuel pavé (box) ou cylindre nettement plus long selon un axe,
l'articulation étant sur cet axe et à moins d'un quart de longueur de ses extrémités. Il indique
alors où finit le segment et quelle origine convient (à 2 mm ou 5 % de la longueur près). Les
articulations prismatiques (un chariot n'importe où sur son rail), celles placées à côté de la
forme du parent (moteurs sur un châssis, roue sous un chariot) et les articulations fixes
(supports de capteurs, repères d'outil) ne sont pas vérifiées.""",
    ),
    "BK302": T(
        title="le visuel d'un segment ne part pas de son articulation",
        message={
            "gap": "le {tag} du link '{link}' commence {distance} m après l'articulation '{joint}' (il occupe {span}) : "
                   "un vide apparaît entre les segments",
            "overlap": "le {tag} du link '{link}' dépasse de {distance} m derrière l'articulation '{joint}' (il occupe {span}) : "
                       "il chevauche le segment précédent",
            "centred": "le {tag} du link '{link}' est centré sur l'articulation '{joint}' (il occupe {span}) : "
                       "sa moitié dépasse derrière l'articulation",
        },
        hint="faites partir le visuel de l'articulation : {origin} dans le <visual> de '{link}'",
        explanation="""\
Un pavé ou un cylindre est centré sur son `<origin>`. Pour qu'un segment parte de son
articulation et s'étende sur sa longueur, l'origine de son visuel doit valoir la moitié de sa
longueur : le bras de 0.6 m du tutoriel a son visuel en z = 0.3. Sans origine (z = 0), la forme
est centrée sur l'articulation et sa moitié dépasse vers l'arrière ; avec une mauvaise valeur,
un vide ou un chevauchement apparaît à l'articulation.""",
    ),
    "BK303": T(
        title="une pose sort des limites d'une articulation",
        message={
            "upper": "articulation '{joint}' = {value} {unit} : {excess} {unit} au-dessus de sa limite haute {bound}",
            "degrees-upper": "articulation '{joint}' = {value} {unit} : {excess} {unit} au-dessus de sa limite haute {bound}",
            "lower": "articulation '{joint}' = {value} {unit} : {excess} {unit} en dessous de sa limite basse {bound}",
            "degrees-lower": "articulation '{joint}' = {value} {unit} : {excess} {unit} en dessous de sa limite basse {bound}",
        },
        hint={
            "": "restez entre {lower} et {upper} {unit}, ou élargissez le <limit> si le mécanisme le permet",
            "degrees-upper": "{value} ressemble à des degrés : écrivez {value}deg ({degrees} rad) ; sinon restez entre {lower} et {upper} {unit}",
            "degrees-lower": "{value} ressemble à des degrés : écrivez {value}deg ({degrees} rad) ; sinon restez entre {lower} et {upper} {unit}",
        },
        explanation="""\
La pose donnée par `--pose` amène une articulation au-delà d'une de ses butées.
robot_state_publisher l'affiche quand même, mais un vrai bras ou un contrôleur s'arrêterait à la
limite (« les articulations dépassent »). Restez entre `lower` et `upper`, ou changez les
limites si le mécanisme permet vraiment d'aller plus loin.""",
    ),
    "BK304": T(
        title="un mouvement sort des limites d'une articulation",
        message={
            "upper": "l'articulation '{joint}' dépasse sa limite haute {bound} {unit} à t={time} s ; "
                     "dépassement maximal {worst} {unit} ({worst_value}) à t={worst_time} s",
            "lower": "l'articulation '{joint}' passe sous sa limite basse {bound} {unit} à t={time} s ; "
                     "dépassement maximal {worst} {unit} ({worst_value}) à t={worst_time} s",
        },
        hint="gardez la commande entre {lower} et {upper} {unit} (amplitude plus petite ou décalage), "
             "ou élargissez le <limit> si le mécanisme le permet",
        explanation="""\
Le mouvement donné par `--motion` (échantillonné à 20 Hz, comme le nœud d'animation du
tutoriel) emmène une articulation hors de ses limites. RViz l'affiche sans broncher, un vrai
bras heurterait sa butée. Le constat donne le premier instant où la limite est franchie et le
plus grand dépassement.""",
    ),
    "BK305": T(
        title="un mouvement dépasse la vitesse maximale",
        message="l'articulation '{joint}' va plus vite que sa vitesse maximale {limit} {unit} à partir de t={time} s ; "
                "pointe à {speed} {unit} à t={worst_time} s",
        hint="ralentissez le mouvement (fréquence ou amplitude plus faible), ou augmentez velocity dans <limit>",
        explanation="""\
La vitesse de l'articulation dans le mouvement dépasse la `velocity` de son `<limit>`. Un
contrôleur saturerait et prendrait du retard sur la consigne ; RViz affiche le mouvement quand
même.""",
    ),
    "BK306": T(
        title="rien ne peut bouger dans ce robot",
        message={
            "fixed": "les {joints} articulations sont fixes : le robot n'a rien à faire bouger",
            "": "le robot n'a aucune articulation : rien ne peut bouger",
        },
        hint='donnez à une articulation un type mobile, par exemple type="revolute" avec un <axis> et un <limit>',
        explanation="""\
Seules les articulations revolute, continuous et prismatic bougent. Sans aucune d'elles,
joint_state_publisher_gui s'ouvre sans curseur et publier sur /joint_states ne change rien
(« le robot ne bouge pas »).""",
    ),
    "BK307": T(
        title="rien à afficher",
        message={
            "collisions": "aucun link n'a de <visual> (seulement des formes <collision>) : RViz n'affiche rien par défaut",
            "": "aucun link n'a de <visual> : RViz n'a rien à dessiner",
        },
        hint="donnez au link '{first}' un <visual> avec une <geometry> (un pavé, un cylindre ou une sphère suffit)",
        explanation="""\
L'affichage RobotModel de RViz dessine le `<visual>` de chaque link. S'il n'y en a aucun,
l'affichage reste vide alors que les repères TF sont bien publiés : c'est l'une des causes de
« RViz reste vide » qui viennent du fichier lui-même (les autres sont les réglages Fixed Frame et
Description Topic).""",
    ),
    # ------------------------------------------------------------------ BK4xx géométrie
    "BK308": T(
        title="un link mobile en bout de chaîne n'a rien à montrer",
        message="le link '{link}' bouge avec l'articulation '{joint}' mais n'a ni <visual> ni enfant : bouger '{joint}' ne change rien à l'écran",
        hint="donnez un <visual> à '{link}' (un petit pavé ou cylindre suffit), ou rendez '{joint}' fixe si ce n'est qu'un repère",
        explanation="""\
RViz ne dessine un link qu'à travers son `<visual>`. Un link accroché à une articulation
mobile, sans enfant ni visuel, ne se voit que dans l'affichage TF : son curseur dans
joint_state_publisher_gui déplace un repère invisible, ce qui ressemble à « le robot ne bouge
pas ». Un repère d'outil qui n'est qu'un repère s'attache plutôt par une articulation `fixed`.""",
    ),
    "BK400": T(
        title="un visuel ou une collision n'a pas de forme",
        message={
            "absent": "un <{tag}> du link '{link}' n'a pas de <geometry>",
            "unknown": "<geometry> contient <{tag}>, qui n'est pas une forme URDF",
            "": "<geometry> est vide",
        },
        hint="mettez une forme dans <geometry> : <box size=...>, <cylinder radius=... length=...>, <sphere radius=...> ou <mesh filename=...>",
        explanation="""\
Chaque `<visual>` et chaque `<collision>` a besoin d'une `<geometry>` contenant exactement une
forme : `box`, `cylinder`, `sphere` ou `mesh`. L'analyseur de ROS échoue sur une géométrie vide
(« Geometry tag contains no child element »).""",
    ),
    "BK401": T(
        title="une dimension est nulle ou négative",
        message={
            "scale": "link '{link}' : l'échelle {value} du <mesh> a une composante nulle : le maillage est aplati",
            "": "link '{link}' : <{tag}> {attribute} {value} n'est pas positif",
        },
        hint={
            "scale": 'mettez 1 pour un axe inchangé, par exemple scale="1 1 1"',
            "": "les dimensions sont des longueurs en mètres et doivent être positives",
        },
        explanation="""\
Les côtés d'un pavé, le rayon et la longueur d'un cylindre, le rayon d'une sphère sont des
longueurs en mètres ; une valeur nulle ou négative ne dessine rien (ou une forme retournée) et
fausse les calculs d'inertie.""",
    ),
    "BK402": T(
        title="un fichier de maillage manque",
        message="link '{link}' : maillage '{filename}' introuvable (cherché en {path})",
        hint="vérifiez le chemin ; un chemin relatif part du dossier du fichier URDF",
        explanation="""\
Le fichier désigné par `<mesh filename=...>` n'existe pas là où un outil ROS le chercherait.
RViz n'affiche alors rien pour ce link. `package://paquet/...` est résolu grâce à
`--package-path` et `BRAS_KIT_PACKAGE_PATH` ; un chemin simple part du dossier du fichier
vérifié.""",
    ),
    "BK403": T(
        title="le paquet d'un maillage est introuvable",
        message="link '{link}' : paquet '{package}' du maillage '{filename}' introuvable, le fichier n'a donc pas été vérifié",
        hint="passez --package-path DOSSIER (un dossier contenant {package}/) ou définissez BRAS_KIT_PACKAGE_PATH",
        explanation="""\
`package://nom/chemin` pointe dans un paquet ROS. Sans ROS, bras-kit cherche les paquets dans
les dossiers donnés par `--package-path` ou `BRAS_KIT_PACKAGE_PATH` (et dans les variables de
ROS si elles existent). Quand le paquet est introuvable, le maillage ne peut pas être vérifié ;
ce n'est qu'un avertissement, car le paquet existe peut-être sur la machine qui fait tourner
ROS.""",
    ),
    "BK404": T(
        title="un maillage est une adresse web",
        message="link '{link}' : le maillage '{url}' est une URL ; bras-kit ne le télécharge pas",
        hint="placez le maillage dans le paquet et utilisez package://PAQUET/meshes/... à la place",
        explanation="""\
Les maillages donnés par une URL http(s) sont téléchargés au lancement par certains outils, et
pas du tout par d'autres. bras-kit ne télécharge jamais rien pendant une vérification : le
maillage n'est donc pas vérifié. Un maillage rangé dans le paquet de description fonctionne
hors ligne et partout.""",
    ),
    "BK405": T(
        title="une composante de couleur sort de 0..1",
        message="matériau '{material}' : rgba {rgba} a des composantes hors de 0..1",
        hint={
            "255": 'les couleurs sont des fractions de 1, pas des octets : rgba="{fixed}"',
            "": 'chacune des valeurs r g b a va de 0 à 1, par exemple rgba="{fixed}"',
        },
        explanation="""\
Les couleurs URDF sont quatre nombres entre 0 et 1 (rouge, vert, bleu, opacité). Des valeurs
écrites comme des octets (0..255) sont ramenées à 1 : la couleur devient blanche ou
délavée.""",
    ),
    "BK406": T(
        title="un matériau est utilisé par son nom sans jamais recevoir de couleur",
        message="le link '{link}' utilise le matériau '{material}', qui n'a de couleur nulle part dans le fichier",
        hint='définissez-le : <material name="{material}"><color rgba="0.5 0.5 0.5 1"/></material>',
        explanation="""\
`<material name="x"/>` sans `<color>` fait référence à un matériau défini ailleurs (au premier
niveau ou dans un visuel précédent). S'il n'existe aucune définition avec une couleur,
l'analyseur de ROS émet un avertissement et le link est dessiné avec la couleur par défaut.""",
    ),
    # ------------------------------------------------------------------ BK5xx inertie
    "BK500": T(
        title="masse nulle ou négative",
        message="link '{link}' : la masse {mass} n'est pas positive",
        hint="donnez la masse en kilogrammes, par exemple <mass value=\"1.0\"/>, ou retirez l'<inertial> d'un link qui n'est qu'un repère",
        explanation="""\
Un simulateur physique divise par la masse ; une masse nulle ou négative fait exploser la
simulation ou refuser le modèle. Les links qui ne sont que des repères (sans corps) ne doivent
pas avoir d'`<inertial>` du tout.""",
    ),
    "BK501": T(
        title="inertie non définie positive",
        message={
            "zero": "link '{link}' : l'inertie est entièrement nulle",
            "": "link '{link}' : l'inertie n'est pas définie positive (moments principaux {moments})",
        },
        hint="calculez-la à partir de la forme et de la masse (bras-kit validate donne les valeurs du solide quand le link a un seul pavé, cylindre ou sphère)",
        explanation="""\
La matrice d'inertie d'un corps doit être définie positive : tous ses moments principaux
strictement positifs. Des moments nuls ou négatifs rendent la dynamique d'un simulateur absurde
(un link qui tourne sans aucun effort). Recopier `ixx="0" iyy="0" izz="0"` en est la cause
habituelle.""",
    ),
    "BK502": T(
        title="les moments principaux violent l'inégalité triangulaire",
        message="link '{link}' : moments principaux {a}, {b}, {c} : la somme des deux plus petits est inférieure au plus grand",
        hint="aucun corps réel n'a ces moments ; recalculez l'inertie à partir de la forme et de la masse",
        explanation="""\
Pour tout corps réel, les moments principaux d'inertie vérifient A + B >= C. Un tenseur qui ne
la respecte pas ne peut venir d'aucune répartition de masse. RViz et robot_state_publisher
n'utilisent pas l'inertie : c'est donc un avertissement, mais les moteurs physiques peuvent
refuser le modèle (MuJoCo le fait, sauf si on lui demande d'équilibrer les inerties) ou le
simuler faux. En général une valeur a été mal tapée, arrondie ou copiée d'un autre link ; bien
des robots publiés en contiennent.""",
    ),
    "BK503": T(
        title="inertie très éloignée de la forme du link",
        message={
            "more": "link '{link}' : {key} = {given} vaut {factor} fois ce que donne un {solid} de {mass} kg ({expected})",
            "less": "link '{link}' : {key} = {given} est {factor} fois plus petit que ce que donne un {solid} de {mass} kg ({expected})",
        },
        hint="pour un solide homogène : {inertia}",
        explanation="""\
L'inertie est comparée à celle d'un solide homogène ayant la forme et la masse du link (pavé :
m(b²+c²)/12 autour de chaque axe ; cylindre : m(3r²+h²)/12 en travers et mr²/2 dans l'axe ;
sphère : 2mr²/5). Un écart de plus d'un facteur 2 signifie en général des axes inversés (un
segment selon z a un petit izz), une erreur d'unité ou des valeurs copiées d'un autre link. Non
vérifié pour les links à plusieurs formes ou à maillage.""",
    ),
    "BK504": T(
        title="centre de masse loin du milieu de la forme du link",
        message={
            "end": "link '{link}' : le centre de masse en xyz {at} est près d'une extrémité de sa forme ({span}), "
                   "pas en son milieu {centre}",
            "outside": "link '{link}' : le centre de masse en xyz {at} est en dehors de sa forme ({span})",
        },
        hint="pour un segment homogène, placez l'origine de l'<inertial> au milieu de la forme : {origin}",
        explanation="""\
L'`<origin>` de `<inertial>` est le centre de masse. L'omettre place la masse à l'origine du
repère du link, c'est-à-dire sur l'articulation : en simulation, le segment se comporte alors
comme si tout son poids était à sa base. Pour un segment homogène, le centre de masse est au
milieu de sa forme (z = 0.3 pour le bras du tutoriel). bras-kit prévient quand il est en dehors
de la forme ou, pour une forme allongée, à plus d'un quart de sa longueur du milieu.""",
    ),
    "BK505": T(
        title="un link mobile n'a pas d'<inertial>",
        message={
            "one": "le link '{link}' est mobile mais n'a pas d'<inertial> : sans importance pour RViz, indispensable pour une simulation physique",
            "": "{count} links mobiles n'ont pas d'<inertial> ({links}) : sans importance pour RViz, indispensable pour une simulation physique",
        },
        hint="ajoutez un <inertial> avec <mass> et <inertia> (essayez bras-kit urdf --inertials pour le bras du tutoriel)",
        explanation="""\
RViz ne fait que dessiner ; il n'utilise jamais la masse ni l'inertie. Un simulateur physique
comme Gazebo ignore, voire refuse, les links sans `<inertial>` : c'est l'exercice « pour aller
plus loin » du tutoriel. Une simple remarque tant que vous ne faites qu'afficher le bras ; elle
est donnée une fois par robot, avec la liste des links.""",
    ),
    "BK506": T(
        title="le link racine a une inertie",
        message="le link racine '{link}' a un <inertial> : robot_state_publisher (KDL) l'ignore et affiche un avertissement",
        hint="sans effet dans RViz ; pour la simulation, ajoutez un link racine sans inertie (par exemple 'world') fixé à '{link}'",
        explanation="""\
KDL, qu'utilise robot_state_publisher, ne gère pas d'inertie sur le link racine et le signale au
démarrage. RViz n'est pas concerné. Les simulateurs qui en ont besoin ajoutent en général un
link racine sans masse (`world` ou `base_footprint`) relié à la vraie base par une articulation
fixe.""",
    ),
}

# BK6xx: the package rules keep their words next to them
from .package.messages_fr import RULE_TEXTS as _PACKAGE_TEXTS  # noqa: E402

RULE_TEXTS.update(_PACKAGE_TEXTS)
