# SPDX-License-Identifier: GPL-2.0-or-later
"""`make compat` end to end on configurations written here (not LinuxCNC's):
preparation, virtual boards and ports, one halrun session per INI, error
lines mapped to their files, the report and the exit status."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))
import compat  # noqa: E402

GOOD_INI = """
[EMCMOT]
EMCMOT = motmod
BASE_PERIOD = 50000
SERVO_PERIOD = 1000000
[KINS]
KINEMATICS = trivkins
JOINTS = 1
[HOSTMOT2]
DRIVER = hm2_pci
CONFIG = "firmware=hm2/5i20/SVST8_4.BIT num_encoders=1 num_pwmgens=1 num_stepgens=1"
[HAL]
HALFILE = good.hal
HALFILE = absent.hal
HALFILE = good.tcl 7
HALCMD = setp parport.0.pin-02-out 1
POSTGUI_HALFILE = panel.hal
"""

GOOD_HAL = """# a configuration as LinuxCNC's sample configs write them
loadrt [KINS]KINEMATICS
loadrt [EMCMOT]EMCMOT base_period_nsec=[EMCMOT]BASE_PERIOD servo_period_nsec=[EMCMOT]SERVO_PERIOD num_joints=[KINS]JOINTS
loadrt hostmot2
loadrt [HOSTMOT2]DRIVER config=[HOSTMOT2]CONFIG
loadrt hal_parport cfg="0x378 out"
loadrt and2 count=1
addf parport.0.read base-thread
addf parport.0.write base-thread
addf motion-command-handler servo-thread
addf motion-controller servo-thread
addf hm2_5i20.0.read servo-thread
addf and2.0 servo-thread
addf hm2_5i20.0.write servo-thread
net xstep joint.0.motor-pos-cmd => hm2_5i20.0.stepgen.00.position-cmd
net both and2.0.out => parport.0.pin-14-out
net in0 parport.0.pin-11-in => and2.0.in0 \\
    <= joint.0.home-sw-in
setp axis.x.jog-scale 1
loadusr -W hal_manualtoolchange
net tool-change iocontrol.0.tool-change => hal_manualtoolchange.change
source good-sub.hal
"""

# a file good.hal sources: prepared by the same rule
GOOD_SUB = """net subpos joint.0.pos-fb => and2.0.in1
"""

GOOD_TCL = """# a Tcl HAL file as LinuxCNC's sim configurations write them
loadrt $::KINS(KINEMATICS)
loadusr -W hal_manualtoolchange
loadrt or2 count=1
addf or2.0 servo-thread
proc wire {n} {
    net tcl-home-$n or2.0.out => joint.$n.home-sw-in
}
for {set j 0} {$j < $::KINS(JOINTS)} {incr j} {
    wire $j
}
setp or2.0.in0 [lindex $::argv 0]-6
net tcl-in or2.0.in1
# as LinuxCNC's hookup_moveoff.tcl does: motion's functions found in the
# servo thread, a joint position pin reconnected (the motion stand-in)
if {![string match "*2 motion-controller*" [hal show thread servo-thread]]} {
    error "motion-controller is not the servo thread's function 2"
}
unlinkp joint.0.motor-pos-cmd
net tcl-pos joint.0.motor-pos-cmd => joint.0.motor-pos-fb
"""

# motmod loaded by a Tcl file (as LinuxCNC's sim_lib.tcl does): the
# stand-in is loaded there, with motmod's num_joints
MOT_INI = """
[KINS]
JOINTS = 2
[HAL]
HALFILE = mot.tcl
"""

MOT_TCL = """loadrt motmod servo_period_nsec=1000000 num_joints=$::KINS(JOINTS)
addf motion-command-handler servo-thread
addf motion-controller servo-thread
net p1 joint.1.motor-pos-cmd => joint.1.motor-pos-fb
net p2 joint.2.motor-pos-cmd => joint.2.motor-pos-fb
set t [hal show thread servo-thread]
if {![string match "*1 motion-command-handler*2 motion-controller*" $t]} {
    error "no motion functions in: $t"
}
"""

BAD_INI = """
[HAL]
HALFILE = bad.hal
HALFILE = bad.tcl
"""

BAD_TCL = """loadrt or2 count=1
proc bad {} {
    setp or2.0.nosuch 1
}
bad
setp or2.0.in0 1
"""

BAD_HAL = """loadrt threads name1=servo-thread period1=1000000
loadrt nosuch_component
setp nosuch_component.0.x 1
loadrt and2 count=1
addf and2.0 servo-thread
"""


Run = tuple[int, str, list[dict[str, object]], Path]


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> tuple[int, str, list[dict[str, object]], Path]:
    for p in (compat.build_dir() / "bin" / n for n in ("halrun", "vboard", "vparport")):
        assert p.exists(), f"{p} is not built (run make)"
    base = tmp_path_factory.mktemp("compat")
    samples = base / "samples"
    for d, ini, hal, tcl in (
        ("good", GOOD_INI, GOOD_HAL, GOOD_TCL),
        ("bad", BAD_INI, BAD_HAL, BAD_TCL),
        ("mot", MOT_INI, "", MOT_TCL),
    ):
        cfg = samples / "set" / d
        cfg.mkdir(parents=True)
        (cfg / f"{d}.ini").write_text(ini)
        (cfg / f"{d}.hal").write_text(hal)
        (cfg / f"{d}.tcl").write_text(tcl)
    (samples / "set" / "good" / "good-sub.hal").write_text(GOOD_SUB)
    (samples / "other" / "x").mkdir(parents=True)
    (samples / "other" / "x" / "x.ini").write_text("[HAL]\nHALFILE = x.hal\n")
    out = base / "out"
    r = subprocess.run(
        [sys.executable, str(HERE / "compat.py"), "--samples", str(samples), "--set", "set/*"]
        + ["--out", str(out), "--keep", str(base / "kept")],
        capture_output=True,
        text=True,
        timeout=600,
    )
    data = json.loads((out / "report.json").read_text())
    return r.returncode, (out / "report.md").read_text(), data, base


def test_exit_status_and_only_the_chosen_set(run: Run) -> None:
    rc, text, data, _ = run
    assert rc == 1, text  # bad.ini fails
    assert [d["ini"] for d in data] == ["set/bad/bad.ini", "set/good/good.ini", "set/mot/mot.ini"]


def test_good_configuration_loads(run: Run) -> None:
    """Motion, kinematics and iocontrol lines out, the board and the port
    virtual, HALCMD run: every present file loads; the absent one is named."""
    _, text, data, _ = run
    good = data[1]
    files = {f["name"]: f for f in good["files"]}  # type: ignore[union-attr]
    assert files["good.hal"]["status"] == "loaded", files["good.hal"]
    assert files["HALCMD"]["status"] == "loaded"
    # the Tcl file ran through haltcl with the same rule: its kinematics
    # and iocontrol commands removed, the net to a joint pin rewritten
    # (made in a procedure called from a loop over an INI value); its
    # HALFILE argument is $::argv
    tcl = files["good.tcl"]
    assert tcl["status"] == "loaded", tcl
    assert tcl["removed"] == {"kinematics": 1, "iocontrol": 1}
    assert tcl["rewritten"] == {"motion": 1}
    assert files["absent.hal"]["status"] == "absent"
    assert good["run_error"] == ""
    assert good["hardware"] == ["vboard 5i20", "vparport"]
    assert good["postgui"] == ["panel.hal"]
    # motion's addf lines and the net of joint.0.motor-pos-cmd are kept:
    # the motion stand-in has them
    assert files["good.hal"]["removed"] == {"kinematics": 1, "motion": 1, "iocontrol": 2}
    # (one rewritten net is in good-sub.hal, which good.hal sources)
    assert files["good.hal"]["rewritten"] == {"board": 2, "motion": 3}
    assert "| set/good/good.ini | good.hal | loaded |" in text


def test_bad_configuration_names_file_line_and_cause(run: Run) -> None:
    _, text, data, _ = run
    files = {f["name"]: f for f in data[0]["files"]}  # type: ignore[union-attr]
    bad = files["bad.hal"]
    assert bad["status"] == "failed"
    assert bad["first_error"] == "bad.hal:2: insmod for nosuch_component failed, returned -1"
    assert "nosuch_component.so" in bad["context"]
    assert bad["errors"] == 2
    assert bad["causes"] == [
        "component nosuch_component",
        "a pin, parameter, signal or function that does not exist (often a consequence)",
    ]
    # a Tcl file stops at its first failing HAL command, named by the
    # file's line (inside a procedure: the line of the command itself)
    tcl = files["bad.tcl"]
    assert tcl["status"] == "failed"
    assert tcl["first_error"] == "bad.tcl:3: parameter or pin 'or2.0.nosuch' not found"
    assert tcl["errors"] == 1
    assert "- 1 × component nosuch_component" in text


def test_prepared_files_keep_their_lines(run: Run) -> None:
    """--keep: the prepared file has the original's lines, removed ones as
    comments, rewritten ones in place."""
    base = run[3]
    prepared = (base / "kept" / "set" / "good" / "good.ini" / "good.hal").read_text().split("\n")
    original = GOOD_HAL.split("\n")
    assert len(prepared) == len(original)
    assert prepared[1].startswith("#compat: removed (kinematics: loadrt trivkins)")
    assert prepared[2].startswith(
        "loadrt threads name1=base-thread period1=[EMCMOT]BASE_PERIOD fp1=0 "
        "name2=servo-thread period2=[EMCMOT]SERVO_PERIOD fp2=1"
    )
    assert prepared[4].startswith("loadrt hm2_sim socket=") and "board=5i20" in prepared[4]
    assert 'cfg="sim:' in prepared[5]
    assert prepared[9:11] == GOOD_HAL.split("\n")[9:11]  # motion's addf lines kept
    assert prepared[14] == "net xstep joint.0.motor-pos-cmd => hm2_5i20.0.stepgen.00.position-cmd"
    assert prepared[16].startswith("net in0 parport.0.pin-11-in => and2.0.in0  #compat")
    assert prepared[17] == "#compat: (continued)"
    sub = (base / "kept" / "set" / "good" / "good.ini" / "good-sub.hal").read_text()
    assert sub.startswith("net subpos => and2.0.in1  #compat"), sub


def test_motion_standin_loaded_by_a_tcl_motmod_line(run: Run) -> None:
    """motmod in a Tcl file: the stand-in is loaded before the command runs,
    with its num_joints (2): joint.1's pins exist, joint.2's net is still
    removed (motmod would not have that joint either)."""
    _, _, data, _ = run
    mot = data[2]
    files = {f["name"]: f for f in mot["files"]}  # type: ignore[union-attr]
    assert mot["run_error"] == ""
    assert files["mot.tcl"]["status"] == "loaded", files["mot.tcl"]
    assert files["mot.tcl"]["removed"] == {"motion": 1}
    assert files["mot.tcl"]["rewritten"] == {"motion": 1}
