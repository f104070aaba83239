// SPDX-License-Identifier: GPL-2.0-or-later
// sim_matrix_kb: a simulated 8x8 key matrix, LinuxCNC 2.9's names and
// keycodes (docs/sim_matrix_kb.md): one key event a period.
component sim_matrix_kb "Convert HAL pin inputs to key matrix keycodes";
pin out u32 out "Keycode: 0xC0 + code at a press, 0x80 + code at a release, 0x40 while keys are held, 0 otherwise";
pin in bit button.c00.r##[8] "Key of column 0, rows 00..07";
pin in bit button.c01.r##[8] "Key of column 1, rows 00..07";
pin in bit button.c02.r##[8] "Key of column 2, rows 00..07";
pin in bit button.c03.r##[8] "Key of column 3, rows 00..07";
pin in bit button.c04.r##[8] "Key of column 4, rows 00..07";
pin in bit button.c05.r##[8] "Key of column 5, rows 00..07";
pin in bit button.c06.r##[8] "Key of column 6, rows 00..07";
pin in bit button.c07.r##[8] "Key of column 7, rows 00..07";
variable unsigned char reported[64];
function _;
license "GPL";
;;
#define KB_PRESS 0xC0u
#define KB_RELEASE 0x80u
#define KB_HELD 0x40u

static int kb_key(struct __comp_state *__comp_inst, int row, int col)
{
    switch (col) {
    case 0:
        return button_c00_r(row);
    case 1:
        return button_c01_r(row);
    case 2:
        return button_c02_r(row);
    case 3:
        return button_c03_r(row);
    case 4:
        return button_c04_r(row);
    case 5:
        return button_c05_r(row);
    case 6:
        return button_c06_r(row);
    case 7:
        return button_c07_r(row);
    default:
        return 0;
    }
}

/* Keys are scanned row by row, column by column; the first key whose
 * state differs from the one last reported is reported (code row * 8 +
 * column) and printed. */
FUNCTION(_) {
    int held = 0;
    for (int code = 0; code < 64; code++) {
        int row = code / 8, col = code % 8;
        int down = kb_key(__comp_inst, row, col) != 0;
        if (down != reported[code]) {
            reported[code] = (unsigned char)down;
            out = (down ? KB_PRESS : KB_RELEASE) | (unsigned)code;
            rtapi_print("row: %d column: %d code: %d\n", row, col, code);
            return;
        }
        held |= down;
    }
    out = held ? KB_HELD : 0;
}
