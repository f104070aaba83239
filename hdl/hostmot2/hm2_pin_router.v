// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_pin_router: connects module signals to I/O pins as the pin
// descriptors say.  The tables are parameters computed by tools/hm2gen from
// the same description as the IDROM, so routing and IDROM cannot disagree.
//
// Outputs: mod_out is the vector of every module output, bit 0 tied to 0
// (layout in README.md).  Pin p's alternate source is
// mod_out[ALT_SRC[16p+15:16p]]; 0 means the pin has no module output.
//
// Inputs: pin_ext = {io_in, 1'b0}, so index 0 is a constant 0 and index p+1
// is I/O pin p.  Encoder i takes A, B, Index and IndexMask from
// pin_ext[ENC_SRC[16(4i+f)+15:16(4i+f)]], f = 0..3, and Probe from
// pin_ext[ENC_PRB_SRC[16i+15:16i]].  The raw pin levels are
// passed on; the encoder bank synchronizes them.  Smart Serial channel j
// receives from pin_ext[SS_RX_SRC[16j+15:16j]] (a channel without an RxData
// pin sees an idle line, 1).
`default_nettype none

module hm2_pin_router #(
    parameter integer IOWIDTH = 24,
    parameter integer MODW    = 1,   // width of mod_out (>= 1, bit 0 = 0)
    parameter integer NENC    = 1,   // encoder slots (>= 1)
    parameter [16*IOWIDTH-1:0] ALT_SRC = {16*IOWIDTH{1'b0}},
    parameter [64*NENC-1:0]    ENC_SRC = {64*NENC{1'b0}},
    parameter [16*NENC-1:0]    ENC_PRB_SRC = {16*NENC{1'b0}},
    parameter integer NSS     = 1,   // Smart Serial channel slots (>= 1)
    parameter [16*NSS-1:0]     SS_RX_SRC = {16*NSS{1'b0}}
) (
    // Not every module output goes to a pin (e.g. step-table bits of a
    // firmware without table pins), and bit 0 is the constant "none".
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [MODW-1:0]    mod_out,
    // Only pins that feed a module input are read here.
    input  wire [IOWIDTH-1:0] io_in,
    /* verilator lint_on UNUSEDSIGNAL */
    output wire [IOWIDTH-1:0] alt_out,
    output wire [NENC-1:0]    enc_a,
    output wire [NENC-1:0]    enc_b,
    output wire [NENC-1:0]    enc_idx,
    output wire [NENC-1:0]    enc_idxmask,
    output wire [NENC-1:0]    enc_probe,
    output wire [NSS-1:0]     ss_rx
);
    wire [IOWIDTH:0] pin_ext = {io_in, 1'b0};

    genvar p, i;
    generate
        for (p = 0; p < IOWIDTH; p = p + 1) begin : g_pin
            localparam integer SRC = {16'd0, ALT_SRC[16*p +: 16]};
            if (SRC > 0 && SRC < MODW) begin : g_mod
                assign alt_out[p] = mod_out[SRC];
            end else begin : g_none
                assign alt_out[p] = 1'b0;
            end
        end
        for (i = 0; i < NENC; i = i + 1) begin : g_enc
            localparam integer SA = {16'd0, ENC_SRC[16*(4*i+0) +: 16]};
            localparam integer SB = {16'd0, ENC_SRC[16*(4*i+1) +: 16]};
            localparam integer SI = {16'd0, ENC_SRC[16*(4*i+2) +: 16]};
            localparam integer SM = {16'd0, ENC_SRC[16*(4*i+3) +: 16]};
            localparam integer SP = {16'd0, ENC_PRB_SRC[16*i +: 16]};
            assign enc_a[i]       = (SA <= IOWIDTH) ? pin_ext[SA] : 1'b0;
            assign enc_b[i]       = (SB <= IOWIDTH) ? pin_ext[SB] : 1'b0;
            assign enc_idx[i]     = (SI <= IOWIDTH) ? pin_ext[SI] : 1'b0;
            assign enc_idxmask[i] = (SM <= IOWIDTH) ? pin_ext[SM] : 1'b0;
            assign enc_probe[i]   = (SP <= IOWIDTH) ? pin_ext[SP] : 1'b0;
        end
        for (i = 0; i < NSS; i = i + 1) begin : g_ss
            localparam integer SR = {16'd0, SS_RX_SRC[16*i +: 16]};
            assign ss_rx[i] = (SR > 0 && SR <= IOWIDTH) ? pin_ext[SR] : 1'b1;
        end
    endgenerate
endmodule

`default_nettype wire
