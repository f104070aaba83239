# SPDX-License-Identifier: GPL-2.0-or-later
"""The rule of `make compat` (docs/compat.md) on lines written for the
purpose: what is removed, rewritten and kept, with line numbers kept."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import halprep as hp  # noqa: E402

INI = hp.parse_ini("""
# a comment
[EMCMOT]
EMCMOT = motmod
BASE_PERIOD = 50000
SERVO_PERIOD = 1000000
[KINS]
KINEMATICS = trivkins coordinates=XYZ
JOINTS = 3
[HOSTMOT2]
DRIVER = hm2_pci
BOARD = 5i20
[HAL]
HALFILE = a.hal
HALFILE = LIB:b.tcl -x
[EMCMOT]
BASE_PERIOD = 1
""")


def act(line: str, ctx: hp.Context | None = None) -> hp.Action:
    return hp.classify(line, INI, ctx or hp.Context())


def test_ini() -> None:
    assert INI.get("EMCMOT", "BASE_PERIOD") == "50000"  # the first value wins
    assert INI.all("HAL", "HALFILE") == ["a.hal", "LIB:b.tcl -x"]
    assert hp.resolve("hm2_[HOSTMOT2](BOARD).0.read [EMCMOT]SERVO_PERIOD", INI) == (
        "hm2_5i20.0.read 1000000"
    )
    assert hp.resolve("[NOPE]KEY [HOSTMOT2](NOPE)", INI) == "[NOPE]KEY [HOSTMOT2](NOPE)"
    files = {"inc.ini": "[X]\nY = 2\n"}
    text = hp.expand_includes("[A]\nB = 1\n#INCLUDE inc.ini\n", files.__getitem__)
    assert hp.parse_ini(text).get("X", "Y") == "2"
    with pytest.raises(ValueError):
        hp.expand_includes("#INCLUDE self\n", lambda p: "#INCLUDE self\n")


@pytest.mark.parametrize(
    "line,part",
    [
        ("loadrt [KINS]KINEMATICS", "kinematics"),
        ("loadrt genserkins", "kinematics"),
        ("loadrt mykins", "kinematics"),
        ("loadrt tpmod", "motion"),
        ("loadrt homemod", "motion"),
        ("addf motion-command-handler servo-thread", "motion"),
        ("addf motion-controller servo-thread", "motion"),
        ("setp joint.0.backlash 0.1", "motion"),
        ("setp axis.x.jog-scale 1", "motion"),
        ("getp motion.servo.last-period", "motion"),
        ("net en <= joint.0.amp-enable-out", "motion"),
        ("linksp Xen joint.0.amp-enable-out", "motion"),
        ("linkps spindle.0.on son", "motion"),
        ("unlinkp iocontrol.0.emc-enable-in", "iocontrol"),
        ("loadusr -W hal_manualtoolchange", "iocontrol"),
        ("loadusr io", "iocontrol"),
        ("loadusr halui", "halui"),
        ("setp halui.joint.jog-speed 2000", "halui"),
        ("loadusr -Wn panel pyvcp -c panel panel.xml", "GUI"),
        ("loadusr -W xyzab-tdr-gui", "GUI"),
        ("net tc iocontrol.0.tool-change => hal_manualtoolchange.change", "iocontrol"),
        ("setp gantrykins.joint-0 0", "kinematics"),
    ],
)
def test_removed(line: str, part: str) -> None:
    a = act(line)
    assert (a.kind, a.part) == ("remove", part)


@pytest.mark.parametrize(
    "line",
    [
        "loadrt pid num_chan=3",
        "loadrt [HOSTMOT2](DRIVER) config=[HOSTMOT2](CONFIG)",
        "addf pid.0.do-pid-calcs servo-thread",
        "setp pid.0.Pgain 1",
        "net xpos-cmd => stepgen.0.position-cmd",
        "net xpos-cmd <= siggen.0.sine",
        "newsig emcmot.00.enable bit",
        "sets emcmot.00.enable FALSE",
        "loadusr -w classicladder --nogui 924.clp",
        "# setp joint.0.x 1",
        "",
    ],
)
def test_kept(line: str) -> None:
    assert act(line).kind == "keep"


def test_net_loses_removed_pins_only() -> None:
    a = act("net xpos joint.0.motor-pos-cmd => stepgen.0.position-cmd ddt.0.in")
    assert (a.kind, a.text) == ("rewrite", "net xpos => stepgen.0.position-cmd ddt.0.in")
    a = act("net X stepgen.0.pos-fb => hm2_[HOSTMOT2](BOARD).0.x <= joint.0.motor-pos-fb")
    assert a.text == "net X stepgen.0.pos-fb => hm2_[HOSTMOT2](BOARD).0.x"  # INI refs kept
    assert "joint.0.motor-pos-fb" in a.why
    a = act("net  tool   iocontrol.0.tool-prep-number  =>  iocontrol.0.tool-prepare")
    assert a.kind == "remove"


def test_motmod_becomes_its_threads() -> None:
    a = act(
        "loadrt [EMCMOT]EMCMOT base_period_nsec=[EMCMOT]BASE_PERIOD "
        "servo_period_nsec=[EMCMOT]SERVO_PERIOD num_joints=[KINS]JOINTS"
    )
    assert a.kind == "rewrite" and a.part == "motion"
    assert a.text == (
        "loadrt threads name1=base-thread period1=[EMCMOT]BASE_PERIOD fp1=0 "
        "name2=servo-thread period2=[EMCMOT]SERVO_PERIOD fp2=1"
    )
    a = act("loadrt motmod servo_period_nsec=500000")
    assert a.text == "loadrt threads name1=servo-thread period1=500000 fp1=1"
    a = act("loadrt motmod base_period_nsec=0 servo_period_nsec=500000")
    assert a.text == "loadrt threads name1=servo-thread period1=500000 fp1=1"


def test_removed_component_names_are_learned() -> None:
    ctx = hp.Context()
    assert act("loadrt genserkins names=arm", ctx).part == "kinematics"
    assert act("setp arm.A-0 1", ctx).kind == "remove"
    assert act("loadusr -Wn mypanel pyvcp -c mypanel p.xml", ctx).part == "GUI"
    assert act("net led mypanel.led <= and2.0.out", ctx).text == "net led <= and2.0.out"
    assert act("setp and2.0.in0 1", ctx).kind == "keep"


def test_own_component_shadows_a_prefix() -> None:
    ctx = hp.Context()
    assert act("setp spindle.0.speed 1", ctx).kind == "remove"
    assert act("loadrt spindle names=spindle", ctx).kind == "keep"
    assert act("setp spindle.0.speed 1", ctx).kind == "keep"


def test_prepare_keeps_line_numbers() -> None:
    text = (
        "loadrt trivkins\n"
        "loadrt pid num_chan=1\n"
        "net a joint.0.x \\\n"
        "   => pid.0.command\n"
        "setp axis.x.y 1 # comment\n"
        "addf pid.0.do-pid-calcs servo-thread\n"
    )
    notes: list[int] = []

    def hook(line: int, joined: str, words: list[str], a: hp.Action) -> hp.Action:
        if words[0] == "addf":
            notes.append(line)
            return hp.Action("rewrite", "board", "test", "addf X servo-thread")
        return a

    p = hp.prepare(text, INI, hp.Context(), hook)
    lines = p.text.split("\n")
    assert len(lines) == len(text.split("\n"))
    assert lines[0].startswith("#compat: removed (kinematics")
    assert lines[1] == "loadrt pid num_chan=1"
    assert lines[2].startswith("net a => pid.0.command  #compat: motion: without joint.0.x")
    assert lines[3] == "#compat: (continued)"
    assert lines[4].startswith("#compat: removed (motion: setp axis.x.y)")
    assert lines[5].startswith("addf X servo-thread  #compat: board: test")
    assert notes == [6]
    assert p.count("remove") == {"kinematics": 1, "motion": 1}
    assert p.count("rewrite") == {"motion": 1, "board": 1}


def test_logical_lines() -> None:
    assert hp.logical_lines("a\\\nb\nc\n") == [(1, 2, "ab"), (3, 3, "c"), (4, 4, "")]


def test_twopass_merge() -> None:
    merged = hp.twopass_merge(
        [
            "loadrt pid names=a,b".split(),
            "loadrt and2 count=1".split(),
            "loadrt pid names=c".split(),
            "loadrt and2 count=2".split(),
            "loadrt hostmot2".split(),
            "loadrt hostmot2".split(),
        ]
    )
    assert merged == ["loadrt pid names=a,b,c", "loadrt and2 count=3", "loadrt hostmot2"]


def test_programs_of_the_configuration() -> None:
    """A vismach view is a GUI, a program importing linuxcnc belongs to the
    task/motion controller; both are removed with their pins."""
    assert hp.program_part("#!/usr/bin/env python3\nfrom vismach import *\n") == "GUI"
    assert hp.program_part("#!/usr/bin/python3\nimport sys, linuxcnc, hal\n") == "motion"
    assert hp.program_part("#!/usr/bin/python3\nimport hal\n") is None
    assert hp.program_part("import vismach\n") is None  # not a program
    ctx = hp.Context()
    ctx.programs["mill"] = "GUI"
    assert act("loadusr -W ./mill", ctx).part == "GUI"
    assert act("net x mill.x <= and2.0.out", ctx).text == "net x <= and2.0.out"


def test_signals_of_removed_nets() -> None:
    """A signal only removed lines created is gone: its sets goes too, until
    a kept net creates it again."""
    ctx = hp.Context()
    assert act("net :x-off gui.x_offset", hp.Context()).kind == "keep"  # unknown comp: kept
    ctx.prefixes["gui."] = "GUI"
    assert act("net :x-off gui.x_offset", ctx).kind == "remove"
    a = act("sets :x-off -20", ctx)
    assert (a.kind, a.part) == ("remove", "GUI")
    assert act("net :x-off and2.0.in0", ctx).kind == "keep"
    assert act("sets :x-off 1", ctx).kind == "keep"


def test_signal_made_by_a_kept_net_stays() -> None:
    """A removed net of a signal a kept net already made leaves it alive:
    a later delsig or sets of it is kept (sim/axis/corexy deletes such
    signals to rewire their pins)."""
    ctx = hp.Context()
    assert act("net j0pos-fb <= stepgen.0.position-fb", ctx).kind == "keep"
    assert act("net j0pos-fb => joint.0.motor-pos-fb", ctx).kind == "remove"
    assert act("delsig j0pos-fb", ctx).kind == "keep"
    # deleted, then only a removed net makes it: gone again
    assert act("net j0pos-fb => joint.0.motor-pos-fb", ctx).kind == "remove"
    assert act("delsig j0pos-fb", ctx).kind == "remove"
    # a newsig makes it alive too
    ctx = hp.Context()
    assert act("newsig s2 float", ctx).kind == "keep"
    assert act("net s2 => joint.1.motor-pos-fb", ctx).kind == "remove"
    assert act("sets s2 1.5", ctx).kind == "keep"


def test_kinematics_line_with_missing_ini_value() -> None:
    a = act("loadrt [NOPE]KINEMATICS")
    assert (a.kind, a.part) == ("remove", "kinematics")
    assert act("loadrt [NOPE]OTHER").kind == "keep"


def test_pendant_absent() -> None:
    """LinuxCNC's xhc-hb04 pendant program is made to fail at once (no
    pendant attached); the lines that name its pins are removed, other
    lines stay."""
    ctx = hp.Context()
    a = act("loadusr -W xhc-hb04 -x -I xhc.ini -H", ctx)
    assert (a.kind, a.part, a.text) == ("rewrite", "pendant", "loadusr -W xhc-hb04-not-attached")
    assert act("setp xhc-hb04.inch-icon 1", ctx).part == "pendant"
    a = act("net pendant:jog-x xhc-hb04.jog.scale => halui.axis.jog-speed", ctx)
    assert (a.kind, a.part) == ("remove", "halui/pendant")
    assert act("setp pid.0.Pgain 1", ctx).kind == "keep"


def test_motion_standin_objects_are_kept_after_motmod() -> None:
    """After a motmod line the stand-in has motion's two functions and the
    position pins of motmod's num_joints joints ([KINS]JOINTS = 3): lines
    naming only those are kept; every other motion object is still removed."""
    ctx = hp.Context()
    assert act("addf motion-controller servo-thread", ctx).kind == "remove"  # no motmod yet
    assert act("loadrt motmod servo_period_nsec=1000 num_joints=[KINS]JOINTS", ctx).kind == (
        "rewrite"
    )
    assert ctx.standin_joints == 3
    for line in (
        "addf motion-command-handler servo-thread",
        "addf motion-controller servo-thread 2",
        "net p joint.2.motor-pos-cmd => joint.2.motor-pos-fb",
        "unlinkp joint.0.motor-pos-cmd",
    ):
        assert act(line, ctx) == hp.KEEP, line
    a = act("net p joint.3.motor-pos-cmd => stepgen.0.position-cmd", ctx)  # no joint 3
    assert (a.kind, a.text) == ("rewrite", "net p => stepgen.0.position-cmd")
    assert act("setp joint.0.backlash 0.1", ctx).part == "motion"
    assert act("net en <= joint.0.amp-enable-out", ctx).kind == "remove"
    assert hp.standin_lines(2) == [
        "loadrt compat_motion names=motion-command-handler,motion-controller",
        "loadrt compat_joint names=joint.0,joint.1",
    ]


@pytest.mark.parametrize(
    "words,joints",
    [
        (["loadrt", "motmod", "num_joints=4"], 4),
        (["loadrt", "motmod"], 16),  # motmod's maximum when not given
        (["loadrt", "motmod", "num_joints=$n"], 16),  # not a number
        (["loadrt", "motmod", "num_joints=40"], 16),
        (["loadrt", "motmod", "num_joints=0"], 1),
    ],
)
def test_motion_standin_joint_count(words: list[str], joints: int) -> None:
    assert hp.motmod_joints(words) == joints
