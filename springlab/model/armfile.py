"""An arm described in a file (TOML or JSON), with units, for :func:`springlab.design.rank.design_arm`.

Every quantity is a number in SI units or a string "value unit"::

    name = "my arm"
    g = "9.81 m/s^2"                 # optional, default 9.81 m/s^2

    [[link]]                         # moving links 2..n, from the ground out
    length = "400 mm"
    com = "0.18 m"                   # from the link's proximal joint
    mass = "12 kg"
    joint = "spherical"              # optional; or a revolute axis [0, 0, 1] in the previous link's frame
    cone = "75 deg"                  # optional, spherical joint: the link within this angle of the previous one
    # range = ["-90 deg", "120 deg"] # optional, revolute joint: the angles it turns through
    radius = "30 mm"                 # optional, the link's radius for clearance (default 25 mm)

    [payload]                        # optional, at the end link's centre of mass
    mass = "2 kg"

    [limits]                         # optional
    max_stiffness = "20 kN/m"
    max_attachment = "0.4 m"         # longest bracket: an end beyond a joint, or up the base post

    [workspace]                      # optional: the poses used to judge spring forces and efficiency
    samples = 2000
    seed = 1

Link numbering follows paper 000: the ground is link 1, so an arm file with k
``[[link]]`` tables describes n = k + 1 links. n above 8 needs ``allow_large``.

Joint limits (``cone``, ``range``) shape the workspace the designs are judged over (their
forces, efficiency and clearance: :func:`springlab.design.rank.workspace_poses`); without
them every link points anywhere, folded poses included.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from springlab import _checks
from springlab.errors import SpringlabError
from springlab.model.chain import limited_poses, serial_chain
from springlab.model.urdf import urdf_to_dict
from springlab.tables import Table

KINDS = {  # kind: (pint dimensionality, SI unit, units to suggest)
    "length": ("[length]", "m", "m, mm, in"),
    "mass": ("[mass]", "kg", "kg, g, lb"),
    "stiffness": ("[mass] / [time] ** 2", "N/m", "N/m, N/mm, lbf/in"),
    "acceleration": ("[length] / [time] ** 2", "m/s^2", "m/s^2, g0"),
    "angle": ("", "rad", "deg, rad"),
}
"""The quantities an arm file holds. A string's unit is read by pint, so any unit pint knows of the
right dimension is accepted ('16 in', '2.2 lbf/in', '1 g0'); a bare number is SI."""
MAX_LINKS = 8

MAX_FILE_BYTES = _checks.MAX_FILE_BYTES
"""The largest arm file read (16 MiB, the limit the URDF reader
shares), checked before it is read."""

LINK_RADIUS = 0.025
"""m: a link's radius where the arm file gives none (a 50 mm tube or casting), for clearance."""


_UNITS = None


def unit_registry():
    """pint's unit registry, made on first use (about 0.3 s; later runs read pint's cache), so that
    an arm file of bare SI numbers, and the CLI's start, do not pay for it."""
    global _UNITS
    if _UNITS is None:
        import pint

        try:
            _UNITS = pint.UnitRegistry(cache_folder=":auto:")
        except OSError:  # no writable cache folder: parse the definitions each time
            _UNITS = pint.UnitRegistry()
    return _UNITS


_OTHER_KINDS = {"force": "[mass] * [length] / [time] ** 2", "speed": "[length] / [time]", "time": "[time]",
                "torque or energy": "[mass] * [length] ** 2 / [time] ** 2"}


def _article(word: str) -> str:
    return f"an {word}" if word[0] in "aeiou" else f"a {word}"


def _kind_of(dimensionality) -> str:
    """'a length', 'a force', ... for a pint dimensionality, or its pint spelling."""
    ureg = unit_registry()
    if dimensionality == ureg.Quantity(1).dimensionality:
        return "a number without dimension"
    for name, dim in [(k, v[0]) for k, v in KINDS.items() if v[0]] + list(_OTHER_KINDS.items()):
        if dimensionality == ureg.get_dimensionality(dim):
            return _article(name)
    return f"a quantity of dimension {dimensionality}"


def parse_quantity(value, kind: str, where: str) -> float:
    """A number (SI) or a string "value unit" of ``kind`` (a key of :data:`KINDS`: 'length' m,
    'mass' kg, 'stiffness' N/m, 'acceleration' m/s^2, 'angle' rad), returned in SI units.
    The unit is read by pint; its dimension must match ``kind``. ``where`` names the field in
    error messages.

    >>> parse_quantity("400 mm", "length", "link 2: length")
    0.4
    >>> parse_quantity("20 kN/m", "stiffness", "limits: max_stiffness")
    20000.0
    """
    if kind not in KINDS:
        raise SpringlabError(f"kind must be one of {tuple(KINDS)}, got {kind!r}")
    dim, si, suggest = KINDS[kind]
    example = f"'1.5 {suggest.split(', ')[0]}'"
    if isinstance(value, bool):
        raise SpringlabError(f"{where} = {value!r}: expected a number or a string like {example}")
    if isinstance(value, int | float):
        try:
            number = float(value)
        except OverflowError:
            raise SpringlabError(f"{where} = {value!r} is too large for a number") from None
    elif isinstance(value, str):
        match = re.fullmatch(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([^\s\d].*?)?\s*", value)
        if not match:
            raise SpringlabError(f"{where} = {value!r} does not parse: write a number and a unit, e.g. {example}")
        number, unit = float(match.group(1)), match.group(2)
        if unit is not None:
            number = _convert(number, unit, kind, where, value)
    else:
        raise SpringlabError(f"{where} = {value!r}: expected a number or a string like {example}")
    if not math.isfinite(number):
        raise SpringlabError(f"{where} = {value!r} is not finite")
    return number


def _convert(number: float, unit: str, kind: str, where: str, value: str) -> float:
    """``number`` ``unit`` in the SI unit of ``kind``, by pint."""
    import pint

    ureg = unit_registry()
    dim, si, suggest = KINDS[kind]
    spelled = unit.replace("²", "^2").replace("³", "^3").replace("°", "deg")
    try:
        parsed = ureg.parse_units(spelled)
    except (pint.errors.UndefinedUnitError, pint.errors.DefinitionSyntaxError, AttributeError, TypeError,
            ValueError, SyntaxError, KeyError, AssertionError) as err:
        name = getattr(err, "unit_names", None) or unit
        name = name[0] if isinstance(name, list | tuple) and name else name
        raise SpringlabError(f"{where} = {value!r}: unknown unit {name!r} for a {kind} (use e.g. {suggest})") from None
    wanted = ureg.get_dimensionality(dim) if dim else ureg.Quantity(1).dimensionality
    if parsed.dimensionality != wanted or (kind == "angle" and ureg.get_root_units(parsed)[1] != ureg.radian):
        raise SpringlabError(f"{where} = {value!r} is {_kind_of(parsed.dimensionality)}, not {_article(kind)}: "
                             f"use a unit such as {suggest}")
    return float(ureg.Quantity(number, parsed).to(si).magnitude)


@dataclass(frozen=True)
class ArmSpec:
    """An arm as a user describes it (SI units). See the module docstring for the file format.

    :ivar r, d, m: lengths, COM distances, masses of the moving links 2..n
    :ivar joints: per moving link 'spherical' or a revolute axis (3-tuple)
    """

    name: str
    r: tuple
    d: tuple
    m: tuple
    joints: tuple
    g: float = 9.81
    payload: float = 0.0
    max_stiffness: float = math.inf
    max_attachment: float | None = None
    samples: int = 2000
    seed: int = 0
    source: str = field(default="", compare=False)
    radius: tuple = ()  # per moving link, m; () for LINK_RADIUS each
    limits: tuple = ()  # per moving link: None, a cone half-angle (rad) or a (low, high) range (rad); () for none
    com_offsets: tuple = ()  # per moving link: its COM's offset from the line, (3,) in its frame (m), projected; () none
    notes: tuple = field(default=(), compare=False)  # what reading the file assumed (a URDF's import)

    def __post_init__(self):
        if not isinstance(self.name, str):
            raise SpringlabError(f"name must be a string, got {self.name!r}")
        for key in ("r", "d", "m", "joints"):
            value = getattr(self, key)
            if isinstance(value, str) or not hasattr(value, "__len__"):
                raise SpringlabError(f"{key} must be a sequence with one entry per moving link, got {value!r}")
            object.__setattr__(self, key, tuple(value))
        if len(self.joints) != len(self.r):
            raise SpringlabError(f"joints must have one entry per moving link ({len(self.r)}), got {len(self.joints)}")
        object.__setattr__(self, "payload", _checks.positive("payload", self.payload, allow_zero=True, unit="kg"))
        object.__setattr__(self, "max_stiffness",
                           _checks.optional_positive("max_stiffness", self.max_stiffness, "N/m", allow_inf=True))
        if self.max_stiffness is None:
            object.__setattr__(self, "max_stiffness", math.inf)
        object.__setattr__(self, "max_attachment", _checks.optional_positive("max_attachment", self.max_attachment, "m"))
        samples = _checks.count("samples", self.samples, least=2,
                                why=" (route 2 judges balance by how the energy varies over the workspace samples)")
        _checks.memory(f"samples = {samples} workspace poses", 6.0 * samples * self.n * 3, hint="use fewer samples")
        object.__setattr__(self, "samples", samples)
        object.__setattr__(self, "seed", _checks.count("seed", self.seed))
        for key in ("radius", "limits", "com_offsets"):
            value = getattr(self, key)
            if isinstance(value, str) or not hasattr(value, "__len__") or len(value) not in (0, len(self.r)):
                raise SpringlabError(f"{key} must have one entry per moving link ({len(self.r)}) or none, got {value!r}")
            object.__setattr__(self, key, tuple(value))
        for j, rad in enumerate(self.radius, start=2):
            _checks.positive(f"link {j}: radius", rad, allow_zero=True, unit="m")
        chain = self.chain()  # validates r, d, m, g and the joints, naming the link
        if self.limits:
            limited_poses(chain, 1, 0, self.limits)  # validates the limits against the joints

    @property
    def n(self) -> int:
        """Links, the ground included (paper 000's n)."""
        return len(self.r) + 1

    @property
    def link_radii(self) -> tuple:
        """Each moving link's radius (m): the file's, or :data:`LINK_RADIUS`."""
        return self.radius or (LINK_RADIUS,) * len(self.r)

    def chain(self, *, with_payload: bool = True):
        """The springlab :class:`~springlab.model.chain.Chain` (payload at the end link's COM)."""
        joints = None if all(j == "spherical" for j in self.joints) else list(self.joints)
        chain = serial_chain(self.r, self.d, self.m, _checks.number("g", self.g), joints=joints)
        return chain.with_payload(self.payload) if with_payload else chain

    def describe(self) -> str:
        """One Markdown line: the arm's name, n, payload (kg), g (m/s^2) and its limits."""
        return (f"**{self.name}** ({self.source}): n = {self.n} links with the ground, payload {self.payload:g} kg, "
                f"g = {self.g:g} m/s², stiffness at most {self.max_stiffness:g} N/m, brackets at most "
                f"{self.max_attachment if self.max_attachment is not None else max(self.r):g} m")

    def table(self) -> Table:
        """The moving links: length (m), COM from the proximal joint (m), mass (kg), joint."""
        return Table(["link", "length (m)", "COM from the proximal joint (m)", "mass (kg)", "joint"],
                     [(j + 2, f"{r:g}", f"{d:g}", f"{m:g}", jt)
                      for j, (r, d, m, jt) in enumerate(zip(self.r, self.d, self.m, self.joints, strict=True))])


def _field(table: dict, key: str, where: str, *, required: bool = True):
    if key not in table:
        if required:
            raise SpringlabError(f"{where}: missing field {key!r}")
        return None
    return table[key]


def arm_from_dict(data: dict, *, source: str = "arm", allow_large: bool = False) -> ArmSpec:
    """Validate a parsed arm description (see the module docstring) into an :class:`ArmSpec`."""
    if not isinstance(data, dict):
        raise SpringlabError(f"{source}: expected a table of fields, got {type(data).__name__}")
    known = {"name", "g", "link", "payload", "limits", "workspace"}
    unknown = sorted(set(data) - known)
    if unknown:
        raise SpringlabError(f"{source}: unknown field(s) {unknown} (known: {sorted(known)})")
    links = _field(data, "link", source)
    if not isinstance(links, list) or not links:
        raise SpringlabError(f"{source}: 'link' must be a list of link tables ([[link]] in TOML), one per moving link")
    n = len(links) + 1
    if n > MAX_LINKS and not allow_large:
        raise SpringlabError(f"{source}: {n} links (ground included) is more than {MAX_LINKS}; designs grow "
                             "combinatorially with n: pass allow_large=True (--allow-large) to try anyway")
    if n < 2:
        raise SpringlabError(f"{source}: need at least one moving link")
    r, d, m, joints, radii, joint_limits = [], [], [], [], [], []
    for idx, link in enumerate(links):
        where = f"{source}: link {idx + 2}"
        if not isinstance(link, dict):
            raise SpringlabError(f"{where}: expected a table with length, com, mass")
        extra = sorted(set(link) - {"length", "com", "mass", "joint", "cone", "range", "radius"})
        if extra:
            raise SpringlabError(f"{where}: unknown field(s) {extra} (known: length, com, mass, joint, cone, range, radius)")
        length = parse_quantity(_field(link, "length", where), "length", f"{where}: length")
        com = parse_quantity(_field(link, "com", where), "length", f"{where}: com")
        mass = parse_quantity(_field(link, "mass", where), "mass", f"{where}: mass")
        if length <= 0:
            raise SpringlabError(f"{where}: length = {length} m must be > 0")
        if mass <= 0:
            raise SpringlabError(f"{where}: mass = {mass} kg must be > 0")
        if not 0 <= com <= length:
            raise SpringlabError(f"{where}: com = {com} m must lie on the link, in [0, {length}] m")
        joint = link.get("joint", "spherical")
        if joint != "spherical":
            if not (isinstance(joint, list) and len(joint) == 3 and all(isinstance(x, int | float) and not isinstance(x, bool) for x in joint)):
                raise SpringlabError(f"{where}: joint = {joint!r}: 'spherical' or a revolute axis [x, y, z]")
            joint = tuple(float(x) for x in joint)
        r.append(length)
        d.append(com)
        m.append(mass)
        joints.append(joint)
        radii.append(None if "radius" not in link else parse_quantity(link["radius"], "length", f"{where}: radius"))
        joint_limits.append(_limit(link, joint, where))
    g = parse_quantity(data.get("g", 9.81), "acceleration", f"{source}: g")
    if g <= 0:
        raise SpringlabError(f"{source}: g = {g} m/s^2 must be > 0")
    payload = 0.0
    if "payload" in data:
        table = data["payload"]
        if not isinstance(table, dict):
            raise SpringlabError(f"{source}: payload must be a table with a mass")
        payload = parse_quantity(_field(table, "mass", f"{source}: payload"), "mass", f"{source}: payload: mass")
        if payload < 0:
            raise SpringlabError(f"{source}: payload: mass = {payload} kg must be >= 0")
    limits = data.get("limits", {})
    if not isinstance(limits, dict):
        raise SpringlabError(f"{source}: limits must be a table")
    extra = sorted(set(limits) - {"max_stiffness", "max_attachment"})
    if extra:
        raise SpringlabError(f"{source}: limits: unknown field(s) {extra} (known: max_stiffness, max_attachment)")
    k_max = math.inf
    if "max_stiffness" in limits:
        k_max = parse_quantity(limits["max_stiffness"], "stiffness", f"{source}: limits: max_stiffness")
    reach = limits.get("max_attachment")
    if reach is not None:
        reach = parse_quantity(reach, "length", f"{source}: limits: max_attachment")
    for name, value in (("max_stiffness", k_max), ("max_attachment", reach)):
        if value is not None and value <= 0:
            raise SpringlabError(f"{source}: limits: {name} = {value} must be > 0")
    ws = data.get("workspace", {})
    if not isinstance(ws, dict):
        raise SpringlabError(f"{source}: workspace must be a table")
    samples, seed = ws.get("samples", 2000), ws.get("seed", 0)
    if not (isinstance(samples, int) and not isinstance(samples, bool) and samples >= 2):
        raise SpringlabError(f"{source}: workspace: samples = {samples!r} must be an integer >= 2 (route 2 judges "
                             "balance by how the energy varies over the workspace samples)")
    if not (isinstance(seed, int) and not isinstance(seed, bool)):
        raise SpringlabError(f"{source}: workspace: seed = {seed!r} must be an integer")
    name = data.get("name", Path(source).stem)
    try:
        radius = () if all(x is None for x in radii) else tuple(LINK_RADIUS if x is None else x for x in radii)
        return ArmSpec(str(name), tuple(r), tuple(d), tuple(m), tuple(joints), g, payload, k_max, reach, samples, seed,
                       source, radius, () if all(x is None for x in joint_limits) else tuple(joint_limits))
    except SpringlabError as err:
        raise SpringlabError(f"{source}: {err}") from None


def _limit(link: dict, joint, where: str):
    """A link's joint limit from its table: a cone half-angle (rad) for a spherical joint, a range
    (low, high) in rad for a revolute one, or None."""
    if "cone" in link and "range" in link:
        raise SpringlabError(f"{where}: give cone (a spherical joint) or range (a revolute joint), not both")
    if "cone" in link:
        if joint != "spherical":
            raise SpringlabError(f"{where}: cone limits a spherical joint; this joint is revolute: give range = [low, high]")
        cone = parse_quantity(link["cone"], "angle", f"{where}: cone")
        if not 0 < cone <= math.pi:
            raise SpringlabError(f"{where}: cone = {link['cone']!r} must be a half-angle in (0, 180] deg")
        return cone
    if "range" in link:
        if joint == "spherical":
            raise SpringlabError(f"{where}: range limits a revolute joint; this joint is spherical: give cone = '<angle>'")
        value = link["range"]
        if not (isinstance(value, list) and len(value) == 2):
            raise SpringlabError(f"{where}: range = {value!r}: give [low, high], e.g. ['-90 deg', '90 deg']")
        lo, hi = (parse_quantity(v, "angle", f"{where}: range") for v in value)
        if not -math.pi <= lo < hi <= math.pi:
            raise SpringlabError(f"{where}: range = {value!r} must satisfy -180 deg <= low < high <= 180 deg")
        return (lo, hi)
    return None


def read_arm_data(path) -> tuple[Path, dict | str]:
    """The checked path of an arm file and its contents: the parsed table of a .toml or .json
    file, the text of a .urdf file."""
    if not isinstance(path, str | Path):
        raise SpringlabError(f"arm file must be a path, got {path!r}")
    path = Path(path)
    if not path.exists():
        raise SpringlabError(f"arm file {path} does not exist")
    if not path.is_file():
        raise SpringlabError(f"arm file {path} is not a file (a directory?): give the path of a .toml or .json file")
    if path.suffix not in (".toml", ".json", ".urdf"):
        if path.suffix.lower() == ".xacro":
            urdf = path.stem if path.stem.endswith(".urdf") else path.stem + ".urdf"
            raise SpringlabError(f"{path} is a xacro file: expand it into a URDF first (xacro {path.name} > {urdf}), "
                                 "then give springlab the .urdf")
        raise SpringlabError(f"{path}: arm files are .toml, .json or .urdf, got {path.suffix!r}")
    try:
        size = path.stat().st_size
    except OSError as err:
        raise SpringlabError(f"{path}: cannot be read ({err.strerror})") from None
    if size > MAX_FILE_BYTES:
        raise SpringlabError(f"{path}: {size / 2 ** 20:.1f} MiB is more than an arm file springlab reads "
                             f"({MAX_FILE_BYTES / 2 ** 20:g} MiB; an arm file is a few kB a link): give the file of "
                             "the arm's own serial chain")
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise SpringlabError(f"{path}: not a text file (UTF-8): an arm file is TOML or JSON text") from None
    except OSError as err:
        raise SpringlabError(f"{path}: cannot be read ({err.strerror})") from None
    if path.suffix == ".urdf":
        return path, text
    if path.suffix == ".toml":
        try:
            import tomllib
        except ImportError:  # Python 3.10
            import tomli as tomllib

        try:
            return path, tomllib.loads(text)
        except tomllib.TOMLDecodeError as err:
            raise SpringlabError(f"{path}: not valid TOML: {err}") from None
    try:
        return path, json.loads(text)
    except (json.JSONDecodeError, RecursionError) as err:
        raise SpringlabError(f"{path}: not valid JSON: {err}") from None


def is_dh_arm(data) -> bool:
    """True for an arm file that describes its arm by DH frames (``[[frame]]``), the form of paper
    001's Table 1, read by :func:`springlab.mechanisms.pseudobase.armfile.load_dh_arm`."""
    return isinstance(data, dict) and "frame" in data


def load_arm(path, *, allow_large: bool = False, up=None, tip: str | None = None, base: str | None = None,
             payload=None) -> ArmSpec:
    """Read an arm file (.toml or .json, or a URDF robot description, .urdf: see
    :mod:`springlab.model.urdf`) into an :class:`ArmSpec`. For a URDF: ``up``, its up direction
    in its root link's frame (default +z, against URDF's gravity); ``tip`` and ``base``, the
    links the arm runs between (every other joint locked at zero); ``payload``, a point mass at
    the tip frame (kg, or a quantity such as '2 kg')."""
    path, data = read_arm_data(path)
    for value, what in ((up, "up"), (tip, "tip"), (base, "base"), (payload, "payload")):
        if value is not None and path.suffix != ".urdf":
            raise SpringlabError(f"{what} = {value!r} applies to URDF files only (an arm file lists its own links"
                                 f"{' and its payload' if what == 'payload' else ''})")
    if path.suffix == ".urdf":
        if payload is not None:
            payload = parse_quantity(payload, "mass", "payload")
        return _from_urdf(data, str(path), allow_large, up, tip=tip, base=base, payload=payload)
    if is_dh_arm(data):
        raise SpringlabError(f"{path} describes its arm by DH frames ([[frame]]), for paper 001's pseudobase "
                             "method: `springlab design` designs it, or load it with "
                             "springlab.mechanisms.pseudobase.armfile.load_dh_arm")
    return arm_from_dict(data, source=str(path), allow_large=allow_large)


def _from_urdf(text: str, source: str, allow_large: bool, up, *, tip=None, base=None, payload=None) -> ArmSpec:
    import dataclasses

    data, arm = urdf_to_dict(text, source=source, up=up, max_links=None if allow_large else MAX_LINKS,
                             tip=tip, base=base, payload=payload)
    spec = arm_from_dict(data, source=source, allow_large=allow_large)
    offsets = tuple(arm.offsets) if any(max(map(abs, o)) > 1e-12 for o in arm.offsets) else ()
    notes = list(arm.notes)
    if offsets:
        worst = max(range(len(offsets)), key=lambda k: math.hypot(*offsets[k]))
        notes.append(f"centres of mass projected onto their links' lines: the largest offset is "
                     f"{math.hypot(*offsets[worst]) * 1e3:.2f} mm (link {worst + 2})")
    return dataclasses.replace(spec, com_offsets=offsets, notes=tuple(notes))
