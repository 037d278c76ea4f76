"""A seeded mutation fuzzer for robodesc's promise about hostile input (docs/security.md).

Each case takes one seed input (URDF, xacro, YAML composition, ``.holo``) and its mesh, applies one
to three mutations (extreme numbers, deleted/duplicated/swapped lines, renamed references, control
characters, deep nesting, truncation, hostile xacro expressions, hostile mesh references, corrupted
mesh bytes), and compiles it for one target (URDF, SDF, USD as ``.usda`` and ``.usdc``, MJCF, the
ROS 2 and the Isaac folders) through ``robodesc.cli.main`` in this process under a ``SIGALRM``
time bound. One case in ten is a batch folder instead (:func:`prepare_batch`): the mutated seed
among other robots, named pipes, Python compositions that must not run without ``--run-python``,
and symlinks in and out of the folder and out of the output folder, through ``robodesc batch``.

A case passes when it ends in

- exit 0, and the output loads (URDF/SDF parse as XML with the right root, USD opens in usd-core,
  MJCF loads in MuJoCo, a folder holds its files named after the input), or
- exit 2, with no traceback, and the output that existed before the run byte-identical;

and fails as ``crash`` (an exception escaped ``main``, a traceback was printed, exit 3 or another
code, a batch job crashed), ``hang`` (the time bound, or a batch job's timeout), ``blame`` (exit 1,
"robodesc's fault": on a mutated source this is either a source defect blamed on robodesc or a real
robodesc bug, and both are to be fixed), ``bad-output`` (exit 0 but the output does not load),
``partial-output`` (a failed run changed the earlier output), ``ran-python`` (a batch ran a Python
file it was not told to) or ``escaped`` (a batch wrote outside its output folder).
One in ten ``validate --dynamics`` and ``render`` cases asks for clips too (``--video``,
:data:`VIDEO`): they must decode, with the expected frame count, and nothing else may be left beside them.
The test tier (``tests/fuzz/run.sh``) also runs each case in a child process, so that a signal
(a segfault in native code) is a ``crash`` and a hang in native code is a ``hang``.
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import os
import random
import re
import shutil
import signal
import traceback
from collections.abc import Callable, Iterator
from pathlib import Path

SEEDS = Path(__file__).parent / "seeds"
SEED_FILES = ("arm.urdf", "arm.urdf.xacro", "four_bar.yaml", "arm.holo")
TARGETS: dict[str, tuple[list[str], str]] = {
    # name -> (CLI options, output name)
    "urdf": (["-t", "urdf"], "out.urdf"),
    "sdf": (["-t", "sdf"], "out.sdf"),
    "usda": (["-t", "usd"], "out.usda"),
    "usdc": (["-t", "usd"], "out.usdc"),
    "isaac": (["--isaac-sim"], "out_isaac"),
    "mjcf": (["-t", "mjcf"], "out_mjcf/robot.xml"),
    "ros2": (["--ros2"], "out_ros2"),
}
# Commands beside compile (issue 34), run from an empty working folder with the input named as a
# relative path, as a user types it: (command line before the input's place, after it, output name).
COMMANDS: dict[str, tuple[list[str], list[str], str | None]] = {
    "view": (["view"], ["-o", "out.html"], "out.html"),
    "render": (["render"], ["-o", "out.png"], "out.png"),
    "dynamics": (["validate"], ["-t", "urdf", "--dynamics", "--engines", "mujoco"], None),
}
# Moving pictures (issue 34): a share of the dynamics and render cases asks for a clip too, drawn
# from a separate random sequence so that every other case stays what it was for a given seed.
# (command -> the case's name, command line after the input, output name in the working folder.)
VIDEO: dict[str, tuple[str, list[str], str]] = {
    "dynamics": ("dynamics-video", [*COMMANDS["dynamics"][1], "--video", "clips"], "clips"),
    "render": ("render-video", ["--video", "out.gif", "--size", "64x48"], "out.gif"),
}
# Of those cases: drawing 2 x 51 frames costs more than the simulation. ROBODESC_FUZZ_VIDEO_SHARE=1
# turns every one of them into a clip case (benchmarks/results/fuzz_tier.md, the video-only run).
VIDEO_SHARE = float(os.environ.get("ROBODESC_FUZZ_VIDEO_SHARE", "0.1"))
FILE_TARGETS = ("urdf", "sdf", "usda", "usdc", "mjcf")
TIME_LIMIT = 30  # seconds per case: far above any honest case (the slowest take ~2 s)
VIDEO_TIME_LIMIT = 80  # a clip case: software GL on a loaded machine; under the tier's 30 + 60 s bound
SENTINEL = b"earlier output: a failed run must leave these bytes alone\n"

EXTREMES = (
    "nan", "inf", "-inf", "1e308", "-1e308", "1.7976931348623157e308", "1e39", "3.5e38", "1e-320", "5e-324",
    "0", "-0", "1e30", "1e31", "1e7", "1e-10", "123456789012345678901234567890", "-1", "99999999999", "1e16",
    "0x10", "1_0", "", " ", "1 2", "1e", "+", "--1",
)  # fmt: skip
HOSTILE_TEXT = ("\x01", "\x1b[31m", "\u202e", "\x7f", "\ufeff", "\u0000", "é", "&amp;", "<", "\t\n", "'", '"', "$", "{")
HOSTILE_XACRO = (
    "${9**9**9}",
    "${python.os}",
    "${xacro.load_yaml('/etc/passwd')}",
    "$(env HOME)",
    "$(optenv HOME none)",
    "${'a' * 10**9}",
    "$(find no_such_package)",
    "${[x for x in range(10**9)]}",
    "${().__class__}",
    "${lambda: 1}",
    "$(eval __import__('os'))",
    "${" + "(" * 300 + "1" + ")" * 300 + "}",
    "${1/0}",
    "${undefined_name}",
)
HOSTILE_MESH = (
    "/etc/passwd",
    "file:///etc/passwd",
    "../../../../../../etc/passwd",
    "/dev/zero",
    "meshes/pipe.stl",
    "meshes/link_to_passwd.stl",
    "package://no_such_pkg/x.stl",
    "package://fuzzpkg/../../../etc/passwd",
    "meshes/broken.stl",
    "meshes/finger.dae",
    "",
    # Issue 34: meshes MJCF converts (ASCII STL) or MuJoCo refuses (empty, NaN), and one outside the
    # input's folder that a converter, the USD writer or a view page might read into its output.
    "meshes/ascii.stl",
    "meshes/empty.obj",
    "meshes/nan.obj",
    "../elsewhere/ascii.stl",
)
ASCII_STL = "solid t\n" + "".join(
    f"facet normal 0 0 1\nouter loop\nvertex {a}\nvertex {b}\nvertex {c}\nendloop\nendfacet\n"
    for a, b, c in (
        ("0 0 0", "0.02 0 0", "0 0.02 0"),
        ("0 0 0", "0 0.02 0", "0 0 0.02"),
        ("0 0 0", "0 0 0.02", "0.02 0 0"),
        ("0.02 0 0", "0 0 0.02", "0 0.02 0"),
    )
) + "endsolid t\n"  # fmt: skip


@dataclasses.dataclass(slots=True)
class Outcome:
    case: int
    seed_file: str
    target: str
    mutations: list[str]
    # ok | refused | crash | hang | blame | bad-output | partial-output | ran-python | escaped |
    # abs-path (a view page names a file by this machine's absolute path) | stray-file (a file left
    # in the working folder)
    status: str
    exit_code: int | None
    detail: str = ""
    case_dir: str = ""

    @property
    def failed(self) -> bool:
        return self.status not in ("ok", "refused")


# ---- mutations ------------------------------------------------------------------------------------

_NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e-?\d+)?(?![\w.])")
_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]{2,}")


def _lines(text: str) -> list[str]:
    return text.split("\n")


def m_number(rng: random.Random, text: str, _d: Path) -> str:
    found = list(_NUMBER.finditer(text))
    if not found:
        return text
    m = rng.choice(found)
    return text[: m.start()] + rng.choice(EXTREMES) + text[m.end() :]


def m_numbers_all(rng: random.Random, text: str, _d: Path) -> str:
    value = rng.choice(EXTREMES[:20])
    return _NUMBER.sub(lambda m: value if rng.random() < 0.3 else m.group(0), text)


def m_delete_line(rng: random.Random, text: str, _d: Path) -> str:
    lines = _lines(text)
    del lines[rng.randrange(len(lines))]
    return "\n".join(lines)


def m_duplicate_line(rng: random.Random, text: str, _d: Path) -> str:
    lines = _lines(text)
    i = rng.randrange(len(lines))
    lines.insert(rng.randrange(len(lines) + 1), lines[i])
    return "\n".join(lines)


def m_swap_lines(rng: random.Random, text: str, _d: Path) -> str:
    lines = _lines(text)
    i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
    lines[i], lines[j] = lines[j], lines[i]
    return "\n".join(lines)


def m_rename(rng: random.Random, text: str, _d: Path) -> str:
    words = list(_WORD.finditer(text))
    if len(words) < 2:
        return text
    m = rng.choice(words)
    other = rng.choice(words).group(0)
    return text[: m.start()] + other + text[m.end() :]


def m_inject_text(rng: random.Random, text: str, _d: Path) -> str:
    words = list(_WORD.finditer(text))
    if not words:
        return text
    m = rng.choice(words)
    return text[: m.end()] + rng.choice(HOSTILE_TEXT) * rng.choice((1, 3, 1000)) + text[m.end() :]


def m_truncate(rng: random.Random, text: str, _d: Path) -> str:
    return text[: rng.randrange(len(text) + 1)]


def m_byte_flip(rng: random.Random, text: str, _d: Path) -> str:
    chars = list(text)
    for _ in range(rng.choice((1, 5, 50))):
        chars[rng.randrange(len(chars))] = chr(rng.randrange(1, 0x3000))
    return "".join(chars)


def m_deep_nesting(rng: random.Random, text: str, d: Path) -> str:
    depth = rng.choice((200, 2000, 50000))
    suffix = d.name
    if suffix.endswith((".yaml", ".yml")):
        return text + f"\nx-deep: {'[' * depth}{']' * depth}\n"
    if suffix.endswith(".holo"):
        i = text.rfind("}")
        return text[:i] + 'object "Deep" { v: ' + "[" * depth + "1" + "]" * depth + " }\n" + text[i:]
    i = text.rfind("</robot>")
    if i < 0:
        return text
    return text[:i] + "<x>" * depth + "</x>" * depth + text[i:]


def m_many_links(rng: random.Random, text: str, d: Path) -> str:
    if not d.name.endswith((".urdf", ".xacro")):
        return text
    i = text.rfind("</robot>")
    if i < 0:
        return text
    n = rng.choice((100, 2000))
    parts = [f'<link name="extra{k}"/><joint name="ej{k}" type="fixed"><parent link="{"base" if k == 0 else f"extra{k - 1}"}"/><child link="extra{k}"/></joint>' for k in range(n)]  # fmt: skip
    return text[:i] + "".join(parts) + text[i:]


def m_hostile_xacro(rng: random.Random, text: str, d: Path) -> str:
    values = list(re.finditer(r'(value|default|name|xyz|size)="([^"]*)"', text))
    if not values:
        return text
    m = rng.choice(values)
    expr = rng.choice(HOSTILE_XACRO).replace("&", "&amp;").replace("<", "&lt;").replace('"', "&quot;")
    return text[: m.start(2)] + expr + text[m.end(2) :]


def m_hostile_mesh(rng: random.Random, text: str, _d: Path) -> str:
    target = rng.choice(HOSTILE_MESH)
    if "meshes/finger.stl" in text:
        return text.replace("meshes/finger.stl", target, 1)
    if "<collision>" in text:  # URDF without the mesh (a mutation removed it): add one
        return text.replace(
            "<collision>", f'<collision><geometry><mesh filename="{target}"/></geometry></collision><collision>', 1
        )
    return text


def m_mesh_bytes(rng: random.Random, text: str, d: Path) -> str:
    """Corrupt the mesh file the seed refers to (the text stays)."""
    mesh = d.parent / "meshes" / "finger.stl"
    data = bytearray(mesh.read_bytes())
    choice = rng.randrange(4)
    if choice == 0:
        data = data[: rng.randrange(len(data))]
    elif choice == 1:
        data[80:84] = (0xFFFFFFF).to_bytes(4, "little")  # absurd triangle count
    elif choice == 2:
        for _ in range(20):
            data[rng.randrange(len(data))] = rng.randrange(256)
    else:
        import struct

        for k in range(84 + 12, len(data) - 4, 50):  # every vertex coordinate extreme
            data[k : k + 4] = struct.pack("<f", rng.choice((float("nan"), float("inf"), 3.0e38, 1e-45)))
    mesh.write_bytes(bytes(data))
    return text


# Defects a source may carry faithfully into its output, which validation must name as the source's
# (issue 34 found each blamed on robodesc, exit 1): (pattern, replacement) in URDF and xacro text.
SOURCE_DEFECTS = (
    (r'<mass value="[^"]*"/>', ""),  # an <inertial> without <mass>
    (r'<inertia ([^/]*)izz="[^"]*"', r'<inertia \1izz="1e30"'),  # a tensor no body has
    (r'damping="[^"]*"', 'damping="-1e30"'),  # energy in, not out
    (r'<sphere radius="([^"]*)"/>', r'<capsule radius="\1" length="0"/>'),  # a zero-length capsule
    (r'upper="[^"]*"', 'upper="1e30"'),  # FK sampled near 6e29 m on a prismatic joint
    (r"<mimic [^>]*/>", ""),  # the prismatic joint sampled on its own
)


def m_source_defect(rng: random.Random, text: str, _d: Path) -> str:
    applicable = [(p, r) for p, r in SOURCE_DEFECTS if re.search(p, text)]
    if not applicable:
        return text
    for pattern, replacement in rng.sample(applicable, min(len(applicable), rng.choice((1, 2, 3)))):
        found = list(re.finditer(pattern, text))
        m = rng.choice(found)
        text = text[: m.start()] + m.expand(replacement) + text[m.end() :]
    return text


MUTATIONS: dict[str, Callable[[random.Random, str, Path], str]] = {
    "number": m_number,
    "numbers": m_numbers_all,
    "delete-line": m_delete_line,
    "duplicate-line": m_duplicate_line,
    "swap-lines": m_swap_lines,
    "rename": m_rename,
    "inject-text": m_inject_text,
    "truncate": m_truncate,
    "byte-flip": m_byte_flip,
    "deep-nesting": m_deep_nesting,
    "many-links": m_many_links,
    "hostile-xacro": m_hostile_xacro,
    "hostile-mesh": m_hostile_mesh,
    "mesh-bytes": m_mesh_bytes,
    "source-defect": m_source_defect,
}
# Mutations more likely to find something are drawn more often.
WEIGHTS = {"number": 5, "numbers": 2, "hostile-xacro": 2, "hostile-mesh": 2, "mesh-bytes": 2, "source-defect": 3}


# ---- one case ---------------------------------------------------------------------------------


BATCH_SHARE = 0.1  # one case in ten is a batch folder
COMMAND_SHARE = 0.25  # of the others, one in four is view, render or validate --dynamics
ESCAPE_SHARE = 0.3  # of the compiles to a file, the share with a meshes link out of the output folder


@dataclasses.dataclass(slots=True)
class Case:
    """One prepared case: the command line, and what the checks after the run need."""

    argv: list[str]
    input: Path  # the mutated seed
    target: str
    mutations: list[str]
    out: Path
    batch: bool = False
    run_python: bool = False
    marker: Path | None = None  # a Python file in a batch folder writes this when it runs
    outside: Path | None = None  # a folder no run may write into
    cwd: Path | None = None  # the working folder the run starts in (it must stay as it was)
    out_name: str | None = None  # what the run may write into ``cwd``
    outside_before: dict[str, bytes] = dataclasses.field(default_factory=dict)


def _mutate(rng: random.Random, seed_file: str, path: Path) -> list[str]:
    text = (SEEDS / seed_file).read_text(encoding="utf-8")
    names = list(MUTATIONS)
    weights = [WEIGHTS.get(n, 1) for n in names]
    applied: list[str] = []
    for _ in range(rng.choice((1, 1, 2, 3))):
        name = rng.choices(names, weights)[0]
        text = MUTATIONS[name](rng, text, path)
        applied.append(name)
    path.write_text(text, encoding="utf-8", errors="surrogatepass")
    return applied


def _case_folder(case_dir: Path) -> None:
    """The meshes and hostile files every case folder holds."""
    (case_dir / "meshes").mkdir(parents=True)
    shutil.copy(SEEDS / "meshes" / "finger.stl", case_dir / "meshes" / "finger.stl")
    (case_dir / "meshes" / "broken.stl").write_bytes(b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 1 2\n")
    (case_dir / "meshes" / "finger.dae").write_bytes(b"<COLLADA><library_geometries/></COLLADA>")
    (case_dir / "package.xml").write_text("<package><name>fuzzpkg</name></package>\n")
    (case_dir / "meshes" / "ascii.stl").write_text(ASCII_STL)
    (case_dir / "meshes" / "empty.obj").write_bytes(b"")
    (case_dir / "meshes" / "nan.obj").write_bytes(b"v nan 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n")
    (case_dir.parent / "elsewhere").mkdir(exist_ok=True)
    (case_dir.parent / "elsewhere" / "ascii.stl").write_text(ASCII_STL)
    with contextlib.suppress(OSError):
        os.mkfifo(case_dir / "meshes" / "pipe.stl")
    with contextlib.suppress(OSError):
        os.symlink("/etc/passwd", case_dir / "meshes" / "link_to_passwd.stl")


def prepare(case: int, seed: int, root: Path) -> Case:
    """Write case ``case`` under ``root``."""
    rng = random.Random(f"{seed}:{case}")
    seed_file = rng.choice(SEED_FILES)
    target = rng.choice(sorted(TARGETS))
    case_dir = root / f"case{case}"
    if case_dir.exists():
        shutil.rmtree(case_dir)
    if rng.random() < BATCH_SHARE:
        return prepare_batch(rng, case_dir, seed_file, target)
    _case_folder(case_dir)
    path = case_dir / seed_file
    applied = _mutate(rng, seed_file, path)
    work = case_dir / "work"  # the run's working folder: empty, and it must stay so
    work.mkdir()
    if rng.random() < COMMAND_SHARE:
        command = rng.choice(sorted(COMMANDS))
        before, after, out_name = COMMANDS[command]
        if command in VIDEO and random.Random(f"{seed}:{case}:video").random() < VIDEO_SHARE:
            command, after, out_name = VIDEO[command]
        argv = [*before, os.path.join("..", seed_file), *after]
        out = work / out_name if out_name else work
        return Case(argv, path, command, applied, out, cwd=work, out_name=out_name)
    options, out_name = TARGETS[target]
    extra = ["--no-validate"] if rng.random() < 0.85 else []  # validation is the slow part: one case in 7
    if rng.random() < 0.2:
        extra.append("--copy-meshes")
    out = case_dir / "o" / out_name
    outside = None
    if target in FILE_TARGETS and rng.random() < ESCAPE_SHARE:
        # A meshes/ beside the output that leads out of it: converted or copied meshes may not go there.
        outside = case_dir / "outside"
        outside.mkdir()
        (outside / "victim.txt").write_text("outside the output folder\n")
        out.parent.mkdir(parents=True, exist_ok=True)
        os.symlink(outside, out.parent / "meshes")
    argv = ["compile", str(path), *options, *extra, "-o", str(out), "-q"]
    return Case(argv, path, target, applied, out, outside=outside, cwd=work)


# A Python composition in a batch folder: it says that it ran (the marker), then its build() does
# one of these. Without --run-python none of it may run.
PYTHON_BODIES = (
    "raise ValueError('a composition bug')",
    "raise SystemExit(0)",
    "return 42",
    "return robodesc.frontends.compose.builder.RobotBuilder",
    "import sys\n    sys.exit('exit from build')",
    "raise KeyboardInterrupt",
)


def prepare_batch(rng: random.Random, case_dir: Path, seed_file: str, target: str) -> Case:
    """A batch folder: the mutated seed and the other seeds, named pipes with robot suffixes, Python
    compositions, symlinks inside the folder, out of it and in a loop; a folder beside it that no
    run may write into, reached through symlinks from the inputs and from the output folder."""
    robots = case_dir / "robots"
    _case_folder(robots)
    outside = case_dir / "outside"
    outside.mkdir()
    (outside / "victim.txt").write_text("outside the output folder\n")
    shutil.copy(SEEDS / "arm.urdf", outside / "secret.urdf")
    (outside / "meshes").mkdir()
    shutil.copy(SEEDS / "meshes" / "finger.stl", outside / "meshes" / "finger.stl")
    path = robots / seed_file
    applied = _mutate(rng, seed_file, path)
    for other in SEED_FILES:
        if other != seed_file and rng.random() < 0.5:
            shutil.copy(SEEDS / other, robots / other)
    for name in ("pipe.urdf", "pipe.yaml", "pipe.holo", "pipe.urdf.xacro", "pipe.py"):
        with contextlib.suppress(OSError):
            os.mkfifo(robots / name)
    marker = case_dir / "python_ran"
    for k, body in enumerate(rng.sample(PYTHON_BODIES, 2)):
        (robots / f"composition{k}.py").write_text(
            f"import robodesc  # a robodesc composition\nimport pathlib\n"
            f"pathlib.Path({str(marker)!r}).write_text('ran')\n\n\ndef build():\n    {body}\n"
        )
    links = {
        "inside_link.urdf": seed_file if seed_file.endswith(".urdf") else "arm.urdf",
        "outside_link.urdf": "../outside/secret.urdf",
        "outside_dir": "../outside",
        "loop": ".",
        "dangling.urdf": "nowhere.urdf",
        "passwd.urdf": "/etc/passwd",
    }
    for name, where in links.items():
        if rng.random() < 0.7:
            os.symlink(where, robots / name)
    out = case_dir / "out"
    extra = ["--no-validate"] if rng.random() < 0.8 else []
    if rng.random() < 0.4:
        extra.append("--copy-meshes")
        # An earlier output folder whose meshes/ leads outside: copying may not write through it.
        for stem in ("arm", "four_bar", "inside_link", "outside_link"):
            (out / stem).mkdir(parents=True, exist_ok=True)
            os.symlink(str(outside / "meshes"), out / stem / "meshes")
    run_python = rng.random() < 0.3
    if run_python:
        extra.append("--run-python")
    options, _ = TARGETS[target]
    if target == "usdc":
        options = [*options, "--suffix", ".usdc"]
    argv = ["batch", str(robots), *options, *extra, "-o", str(out), "-q", "-j", "1", "--timeout", "20"]
    return Case(argv, path, target, ["batch", *applied], out, True, run_python, marker, outside)


class _Timeout(BaseException):
    """Raised by the alarm; a BaseException so that robodesc's ``except Exception`` cannot eat it."""


@contextlib.contextmanager
def _alarm(seconds: int) -> Iterator[None]:
    def fire(_signum: int, _frame: object) -> None:
        raise _Timeout

    previous = signal.signal(signal.SIGALRM, fire)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)


def _snapshot(path: Path) -> dict[str, bytes]:
    if path.is_dir():
        return {str(p.relative_to(path)): p.read_bytes() for p in sorted(path.rglob("*")) if p.is_file()}
    return {"": path.read_bytes()} if path.exists() else {}


def _plant_sentinel(out: Path) -> None:
    if out.suffix:  # a file target
        out.write_bytes(SENTINEL)
    else:
        out.mkdir()
        (out / "earlier.txt").write_bytes(SENTINEL)


def input_stem(path: Path) -> str:
    """``arm.urdf.xacro`` -> ``arm``: what a folder target names its files after."""
    name = path.name.removesuffix(".xacro")
    return name.rsplit(".", 1)[0]


def check_output(target: str, out: Path, source: Path | None = None) -> str | None:
    """Why the output of a successful run does not load, or ``None``."""
    from lxml import etree

    try:
        if target == "dynamics":
            return None  # nothing written
        if target == "render":
            return None if out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" else "not a PNG"
        if target in ("dynamics-video", "render-video"):
            return _clip_problem(target, out)
        if target == "view":
            return _page_problem(out)
        if target in ("urdf", "sdf"):
            root = etree.parse(str(out)).getroot()
            if root.tag != ("robot" if target == "urdf" else "sdf"):
                return f"root element is <{root.tag}>"
            return None
        if target == "mjcf":
            import mujoco

            mujoco.MjModel.from_xml_path(str(out))
            return None
        stem = input_stem(source) if source is not None else None
        if target == "ros2":
            urdfs = sorted(out.glob("*.urdf"))
            if not urdfs:
                return "no URDF in the ROS 2 folder"
            if stem is not None and urdfs[0].name != f"{stem}.urdf":
                return f"the ROS 2 folder's URDF is {urdfs[0].name}, not named after the input {source.name}"
            if etree.parse(str(urdfs[0])).getroot().tag != "robot":
                return "the ROS 2 URDF's root is not <robot>"
            return None
        from pxr import Usd

        usd = (
            out
            if target != "isaac"
            else next(iter(sorted(p for p in out.glob("*.usd*") if not p.name.endswith("_physics.usda"))), None)
        )
        if usd is None:
            return "no USD file in the Isaac folder"
        if target == "isaac" and stem is not None and usd.name != f"{stem}.usda":
            return f"the Isaac folder's USD is {usd.name}, not named after the input {source.name}"
        stage = Usd.Stage.Open(str(usd))
        if stage is None or not stage.GetDefaultPrim():
            return "usd-core opens no stage with a default prim"
        return None
    except Exception as exc:  # the consumer's own failure is the finding
        return f"{type(exc).__name__}: {exc}"


def _clip_problem(target: str, out: Path) -> str | None:
    """Why the clips of a successful run are not: a file that does not decode or has the wrong
    frame count, a temporary left, or the earlier file beside them changed."""
    from robodesc.view.video import FPS, SWEEP_SECONDS, read_frames

    if target == "render-video":
        from PIL import Image, ImageSequence

        # Pillow's GIF writer merges identical consecutive frames into one of their summed
        # duration (two poses a pixel apart at 64x48): the playing time is what must hold.
        expected = round(SWEEP_SECONDS * FPS) + 1
        with Image.open(out) as gif:
            played = sum(int(f.info.get("duration", 0)) for f in ImageSequence.Iterator(gif))
        frames = len(read_frames(str(out)))
        if played != expected * round(1000 / FPS) or frames < 2:
            return f"{frames} frames playing {played} ms, not {expected} frames of {round(1000 / FPS)} ms"
        return None
    names = sorted(os.listdir(out))
    if (out / "earlier.txt").read_bytes() != SENTINEL:
        return "the file beside the clips changed"
    for name in names:
        if name == "earlier.txt":
            continue
        if not name.endswith((".mp4", ".gif")) or name.startswith("."):
            return f"{name} left in the clips' folder"
        if len(read_frames(str(out / name))) < 2:
            return f"{name} has fewer than two frames"
    return None


def _page_problem(page: Path) -> str | None:
    """Why a view page is not one: no scene data, or data that is not JSON."""
    import json

    text = page.read_text(encoding="utf-8")
    found = re.search(r'<script id="robodesc-data" type="application/json">(.*?)</script>', text, re.S)
    if found is None:
        return "no scene data in the page"
    json.loads(found.group(1).replace("<\\/", "</"))
    return None


def _absolute_path(case: Case) -> str | None:
    """A view page made from an input named relatively must not name the case's folder by its
    absolute path (a page is made to be shared)."""
    if case.target != "view" or not case.out.is_file():
        return None
    text = case.out.read_text(encoding="utf-8", errors="replace")
    root = str(case.input.parent)
    for folder in {root, os.path.realpath(root)}:
        at = text.find(folder + os.sep)
        if at >= 0:
            return f"the page names {text[at : at + 120]!r}"
    return None


def _stray(case: Case) -> str | None:
    """A file the run left in its working folder, other than the output it was told to write there."""
    if case.cwd is None or not case.cwd.is_dir():
        return None
    left = sorted(set(os.listdir(case.cwd)) - {case.out_name})
    return f"left {left} in the working folder" if left else None


def _classify(case: Case, code: int, err: str, before: dict[str, bytes], outcome: Outcome) -> None:
    outcome.exit_code = code
    if "Traceback (most recent call last)" in err:
        outcome.status, outcome.detail = "crash", err[-3000:]
    elif (stray := _stray(case)) is not None:
        outcome.status, outcome.detail = "stray-file", stray
    elif case.outside is not None and _snapshot(case.outside) != case.outside_before:
        outcome.status, outcome.detail = "escaped", "the run wrote through a meshes link out of its output folder"
    elif code == 0 and (absolute := _absolute_path(case)) is not None:
        outcome.status, outcome.detail = "abs-path", absolute
    elif code == 0:
        problem = check_output(case.target, case.out, case.input)
        if problem is not None:
            outcome.status, outcome.detail = "bad-output", problem
    elif code == 1:
        outcome.status = "blame"
        outcome.detail = err.strip().splitlines()[0] if err.strip() else ""
    elif code == 2:
        outcome.status = "refused"
        outcome.detail = err.strip().splitlines()[0] if err.strip() else ""
        if case.target != "dynamics" and _snapshot(case.out) != before:
            outcome.status = "partial-output"
            outcome.detail = f"exit {code} changed the earlier output: {outcome.detail}"
    else:
        outcome.status, outcome.detail = "crash", f"exit code {code}: {err[-2000:]}"


def _classify_batch(case: Case, code: int, err: str, outside: dict[str, bytes], outcome: Outcome) -> None:
    """A batch's exit code follows its jobs (0 all ok, 1 a validation failed, 2 a job failed): the
    jobs' outcomes in summary.json say which were crashes, timeouts and blames."""
    import json

    outcome.exit_code = code
    jobs: list[dict[str, object]] = []
    summary_file = case.out / "summary.json"
    if summary_file.is_file():
        jobs = json.loads(summary_file.read_text(encoding="utf-8"))["jobs"]
    by_status = {str(j["status"]): j for j in jobs}
    first = err.strip().splitlines()[0] if err.strip() else ""
    if "Traceback (most recent call last)" in err:
        outcome.status, outcome.detail = "crash", err[-3000:]
    elif code not in (0, 1, 2):
        outcome.status, outcome.detail = "crash", f"exit code {code}: {err[-2000:]}"
    elif "crashed" in by_status:
        outcome.status, outcome.detail = (
            "crash",
            f"job {by_status['crashed'].get('id')}: {by_status['crashed'].get('error')}",
        )
    elif "timeout" in by_status:
        outcome.status, outcome.detail = "hang", f"job {by_status['timeout'].get('id')} timed out"
    elif case.marker is not None and case.marker.exists() and not case.run_python:
        outcome.status, outcome.detail = "ran-python", "a Python file in the folder ran without --run-python"
    elif case.outside is not None and _snapshot(case.outside) != outside:
        outcome.status, outcome.detail = "escaped", "the batch wrote into a folder outside its output"
    elif code == 1 or "validation-failed" in by_status:
        job = by_status.get("validation-failed", {})
        outcome.status, outcome.detail = "blame", f"job {job.get('id')}: {job.get('error')} {first}"
    elif not summary_file.is_file() and code != 2:
        outcome.status, outcome.detail = "crash", f"exit {code} without summary.json: {first}"
    else:
        outcome.status = "ok" if code == 0 else "refused"
        outcome.detail = first


def run_case(case: int, seed: int, root: Path, time_limit: int = TIME_LIMIT) -> Outcome:
    from robodesc.cli import main

    prepared = prepare(case, seed, root)
    out = prepared.out
    outcome = Outcome(
        case, prepared.input.name, prepared.target, prepared.mutations, "ok", None, case_dir=str(prepared.input.parent)
    )
    if prepared.batch:
        outcome.case_dir = str(prepared.input.parent.parent)
        outcome.target = f"batch-{prepared.target}"
        before = _snapshot(prepared.outside) if prepared.outside else {}
    else:
        if prepared.outside is not None:
            prepared.outside_before = _snapshot(prepared.outside)
        if prepared.target != "dynamics":
            out.parent.mkdir(parents=True, exist_ok=True)
            _plant_sentinel(out)
        before = _snapshot(out) if prepared.target != "dynamics" else {}
    stdout, stderr = io.StringIO(), io.StringIO()
    argv = prepared.argv
    if prepared.target.endswith("-video"):
        time_limit = max(time_limit, VIDEO_TIME_LIMIT)
    here = os.getcwd()
    try:
        if prepared.cwd is not None:
            os.chdir(prepared.cwd)
        with _alarm(time_limit), contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
            code = main(argv)
    except _Timeout:
        outcome.status, outcome.detail = "hang", f"no answer within {time_limit} s: robodesc {' '.join(argv)}"
        return outcome
    except BaseException as exc:  # anything escaping main() is the finding
        outcome.status = "crash"
        outcome.detail = "".join(traceback.format_exception(exc))[-3000:]
        return outcome
    finally:
        os.chdir(here)
    err = stderr.getvalue()
    if prepared.batch:
        _classify_batch(prepared, code, err, before, outcome)
    else:
        _classify(prepared, code, err, before, outcome)
    if not outcome.failed:
        shutil.rmtree(outcome.case_dir, ignore_errors=True)
    return outcome


def run(cases: int, seed: int, root: Path, first: int = 0) -> list[Outcome]:
    return [run_case(i, seed, root) for i in range(first, first + cases)]


def summary(outcomes: list[Outcome]) -> str:
    from collections import Counter

    by_status = Counter(o.status for o in outcomes)
    lines = [f"{len(outcomes)} cases: " + ", ".join(f"{n} {s}" for s, n in sorted(by_status.items()))]
    for o in outcomes:
        if o.failed:
            lines.append(
                f"  case {o.case} [{o.seed_file} -> {o.target}, {'+'.join(o.mutations)}] {o.status}: "
                f"{o.detail.strip().splitlines()[-1] if o.detail.strip() else ''} ({o.case_dir})"
            )
    return "\n".join(lines)


if __name__ == "__main__":  # python tests/fuzz/fuzzer.py CASES [SEED] [DIR]: the long mode by hand
    import sys
    import tempfile

    count = int(sys.argv[1]) if len(sys.argv) > 1 else 200
    base_seed = int(sys.argv[2]) if len(sys.argv) > 2 else 17
    where = Path(sys.argv[3]) if len(sys.argv) > 3 else Path(tempfile.mkdtemp(prefix="robodesc-fuzz-"))
    results = []
    for i in range(count):
        results.append(run_case(i, base_seed, where))
        if results[-1].failed:
            print(summary([results[-1]]).splitlines()[-1], flush=True)
    print(summary(results))
