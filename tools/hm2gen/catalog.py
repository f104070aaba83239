# SPDX-License-Identifier: GPL-2.0-or-later
"""The module types hm2gen knows: the values their IDROM module descriptor
publishes (spec/hostmot2.md sections 4, 6, 9) and their pin signals (section
7).  A firmware description names a type and an instance count; everything
else in the descriptor comes from here, so it is written exactly once."""

from __future__ import annotations

from dataclasses import dataclass, field

CLOCK_LOW = 1
CLOCK_HIGH = 2
OUT = 0x80  # SecPin bit 7: the module drives the pin


@dataclass(frozen=True)
class ModuleType:
    name: str  # name used in descriptions, JSON and the .PIN file
    gtag: int
    version: int
    clock_tag: int
    base: int
    registers: int
    strides: int  # raw Strides byte of the MD
    mp_bitmap: int
    # signal name -> raw SecPin byte (bit 7 = output)
    signals: dict[str, int] = field(default_factory=dict)
    # False: the firmware has no logic for this module (see docs/hm2gen.md);
    # its pins keep their descriptors but it gets no module descriptor.
    implemented: bool = True
    max_instances: int = 64
    # Printed in the .PIN file like Mesa's tools print it.
    pin_name: str = ""
    # Other MD versions a firmware may publish with a 'version' key (the
    # newer register sets the module implements), e.g. the probe-capable
    # encoder 0x83 and the StepGen with swap step/dir 0x42.
    alt_versions: tuple[int, ...] = ()

    def signal_name(self, code: int) -> str:
        for k, v in self.signals.items():
            if v == code:
                return k
        raise KeyError(code)


def _ssr_signals() -> dict[str, int]:
    sig: dict[str, int] = {}
    for k in range(8):
        sig[f"TxData{k}"] = OUT | (0x01 + k)
    for k in range(8):
        sig[f"TxEn{k}"] = OUT | (0x11 + k)
    for k in range(8):
        sig[f"RxData{k}"] = 0x01 + k
    return sig


MODULES: dict[str, ModuleType] = {
    m.name: m
    for m in (
        ModuleType(
            "Watchdog", 2, 0, CLOCK_LOW, 0x0C00, 3, 0x00, 0x00, max_instances=1, pin_name="WatchDog"
        ),
        ModuleType("IOPort", 3, 0, CLOCK_LOW, 0x1000, 5, 0x00, 0x1F, pin_name="IOPort"),
        ModuleType(
            "Encoder",
            4,
            2,
            CLOCK_LOW,
            0x3000,
            5,
            0x00,
            0x03,
            signals={"A": 0x01, "B": 0x02, "Index": 0x03, "IndexMask": 0x04, "Probe": 0x05},
            pin_name="QCount",
            alt_versions=(0x83,),
        ),
        ModuleType(
            "StepGen",
            5,
            2,
            CLOCK_LOW,
            0x2000,
            10,
            0x00,
            0x1FF,
            signals={
                "Step": OUT | 1,
                "Direction": OUT | 2,
                **{f"Table{k}": OUT | (k + 1) for k in range(2, 8)},
            },
            pin_name="StepGen",
            alt_versions=(0x42,),
        ),
        ModuleType(
            "PWMGen",
            6,
            0,
            CLOCK_HIGH,
            0x4000,
            5,
            0x00,
            0x03,
            signals={"Out0": OUT | 1, "Out1": OUT | 2, "NotEnable": OUT | 3},
            max_instances=32,  # one enable-register bit per instance
            pin_name="PWM",
        ),
        ModuleType(
            "TranslationRAM",
            11,
            0,
            CLOCK_LOW,
            0x7800,
            4,
            0x00,
            0x00,
            max_instances=1,
            pin_name="AddrX",
        ),
        ModuleType(
            "LED", 128, 0, CLOCK_LOW, 0x0200, 1, 0x00, 0x00, max_instances=1, pin_name="LED"
        ),
        ModuleType(
            "SSerial",
            193,
            0,
            CLOCK_LOW,
            0x5A00,
            6,
            0x10,
            0x3C,
            signals=_ssr_signals(),
            # hm2_sserial.v: Mesa's host registers and IDROM entry, but a
            # remote wire protocol of our own, not Mesa's SSLBP
            # (docs/hm2-firmware.md).
            max_instances=4,
            pin_name="SSerial",
        ),
    )
}

GTAG_NAMES: dict[int, str] = {m.gtag: m.name for m in MODULES.values()}

# Stock strides (spec section 8).
INSTANCE_STRIDE0 = 4
INSTANCE_STRIDE1 = 64
REGISTER_STRIDE0 = 256
REGISTER_STRIDE1 = 256
