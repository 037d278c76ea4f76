"""Whether the root link is welded to the world or floats: one decision for every target (docs/isaac.md,
"The base").

Decided once, before any emitter runs, so that USD, the Isaac folder (and its Isaac Lab module), SDF
and MJCF never disagree about one robot, and ``validate --dynamics`` simulates the base the files
have. In order, the first that says wins:

1. a root link called ``world``: the source welds the robot itself (URDF's convention), and no
   target can float it, whatever the flags say;
2. ``--fix-base`` / ``--no-fix-base`` (``fix_base=`` in the API);
3. a composition's ``base: fixed | floating`` (``Robot.fixed_base``);
4. the legs: a robot that stands on three or more legs (:func:`robodesc.emit.common.stance.find_legs`
   at the zero pose) floats, so that it stands on them; anything else (an arm, a hand, a biped, whose
   balance needs a controller) is welded, as Isaac's importer and most arm setups do.
"""

from __future__ import annotations

from dataclasses import dataclass

from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot

MIN_LEGS = 3  # legs a robot needs to stand without a controller's balance

# The reason strings say what decided; the summary line prints them after the word.
BY_FLAG = "given"
BY_WORLD = "the source's root link is 'world'"
BY_COMPOSITION = "the composition's base"


@dataclass(frozen=True, slots=True)
class BaseChoice:
    fixed: bool
    reason: str  # what decided, said in the summary line
    legs: tuple[str, ...] = ()  # the feet found, when the legs decided

    @property
    def word(self) -> str:
        return "fixed" if self.fixed else "floating"

    def summary(self) -> str:
        """``base: floating (stands on 4 feet; --fix-base to weld)``: what applied, why, and the flag
        that would change it (none when the source's ``world`` root decides)."""
        other = (
            "" if self.reason == BY_WORLD else ("; --no-fix-base to float" if self.fixed else "; --fix-base to weld")
        )
        why = f"--{'' if self.fixed else 'no-'}fix-base" if self.reason == BY_FLAG else self.reason
        return f"base: {self.word} ({why}{'' if self.reason == BY_FLAG else other})"


def choose_base(robot: Robot, given: bool | None) -> BaseChoice:
    """The base of ``robot``; ``given`` is the user's ``fix_base`` (None when not given)."""
    if robot.root.name == "world":
        return BaseChoice(True, BY_WORLD)
    if given is not None:
        return BaseChoice(given, BY_FLAG)
    if robot.fixed_base is not None:
        return BaseChoice(robot.fixed_base, BY_COMPOSITION)
    # Loaded here: target modules import this one to build the CLI's parser, and find_legs reads meshes.
    from robodesc.emit.common.stance import complete, find_legs

    legs = find_legs(robot, complete(robot, {}))
    if len(legs) >= MIN_LEGS:
        return BaseChoice(False, f"stands on {len(legs)} feet", tuple(leg.foot for leg in legs))
    shape = "no legs" if not legs else f"{len(legs)} legs"
    return BaseChoice(True, f"{shape}: fewer than {MIN_LEGS} to stand on")


def report_base(robot: Robot, choice: BaseChoice, findings: Findings) -> None:
    """The floating default said as a finding, with its feet (the Isaac folder's findings.md lists it);
    a weld is the importers' default and needs no note beyond the summary line."""
    if choice.fixed or not choice.legs:
        return
    findings.info(
        "base-floating",
        f"{len(choice.legs)} legs ({', '.join(choice.legs)}): the root floats in every target so the robot "
        "stands on them; --fix-base welds it to the world",
        element=f"robot {robot.name!r}",
        stage="options",
    )
