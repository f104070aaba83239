// SPDX-License-Identifier: GPL-2.0-or-later
//
// epp_fixture: test-only wiring that lets a Python coroutine play the EPP
// peripheral, so the EPP host model's checks can be tested against
// peripherals that break the protocol on purpose.  The peripheral side
// (p_*) is fed straight to the pins the host model watches.
`default_nettype none

module epp_fixture (
    input  wire       clk,
    input  wire [7:0] epp_d_i,
    output wire [7:0] epp_d_o,
    output wire       epp_d_oe,
    input  wire       epp_nwrite,
    input  wire       epp_ndatastr,
    input  wire       epp_naddrstr,
    input  wire       epp_nreset,
    output wire       epp_nwait,
    input  wire [7:0] p_d_o,
    input  wire       p_d_oe,
    input  wire       p_nwait
);
    assign epp_d_o   = p_d_o;
    assign epp_d_oe  = p_d_oe;
    assign epp_nwait = p_nwait;
    wire unused_ok = &{1'b0, clk, epp_d_i, epp_nwrite, epp_ndatastr, epp_naddrstr, epp_nreset};
endmodule

`default_nettype wire
