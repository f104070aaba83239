// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_top_epp: a HostMot2 firmware for an EPP board (7i43): the EPP
// bridge (hm2_epp_bridge) in front of the generic core (hm2_core).  reconfig
// pulses when the host asks the CPLD to reload the FPGA.  Every
// parameter comes from the generated include of one firmware description
// (tools/hm2gen); see hm2_core.v for their meaning.
`default_nettype none

module hm2_top_epp #(
    parameter integer IOPORTS        = 1,
    parameter integer PORTWIDTH      = 24,
    parameter integer NUM_LEDS       = 2,
    parameter integer NUM_STEPGEN    = 1,
    parameter integer SG_TABLE_WIDTH = 2,
    parameter integer NUM_ENCODER    = 1,
    parameter integer NUM_PWMGEN     = 1,
    parameter integer CLOCK_LOW_HZ   = 33333333,  // ClockLow (encoder filter reset value)
    parameter [15:0]  WD_BASE        = 16'h0C00,
    parameter [15:0]  IO_BASE        = 16'h1000,
    parameter [15:0]  LED_BASE       = 16'h0200,
    parameter [15:0]  SG_BASE        = 16'h2000,
    parameter [15:0]  ENC_BASE       = 16'h3000,
    parameter [15:0]  PWM_BASE       = 16'h4000,
    parameter integer NUM_XLAT       = 0,
    parameter [15:0]  XLAT_BASE      = 16'h7800,
    parameter integer NUM_SSERIAL    = 0,
    parameter integer SS_NCHAN       = 1,
    parameter integer SS_DIV         = 13,
    parameter [15:0]  SS_BASE        = 16'h5A00,
    parameter [16*(NUM_SSERIAL > 0 ? NUM_SSERIAL*SS_NCHAN : 1)-1:0] SS_RX_SRC =
        {16*(NUM_SSERIAL > 0 ? NUM_SSERIAL*SS_NCHAN : 1){1'b0}},
    parameter [8191:0] IDROM         = {8192{1'b0}},
    parameter [16*IOPORTS*PORTWIDTH-1:0] ALT_SRC = {16*IOPORTS*PORTWIDTH{1'b0}},
    parameter [64*(NUM_ENCODER > 0 ? NUM_ENCODER : 1)-1:0] ENC_SRC =
        {64*(NUM_ENCODER > 0 ? NUM_ENCODER : 1){1'b0}},
    parameter [16*(NUM_ENCODER > 0 ? NUM_ENCODER : 1)-1:0] ENC_PRB_SRC =
        {16*(NUM_ENCODER > 0 ? NUM_ENCODER : 1){1'b0}}
) (
    input  wire                           clk_low,
    input  wire                           clk_high,
    input  wire                           rst,
    input  wire [7:0]                     epp_d_i,
    output wire [7:0]                     epp_d_o,
    output wire                           epp_d_oe,
    input  wire                           epp_nwrite,
    input  wire                           epp_ndatastr,
    input  wire                           epp_naddrstr,
    output wire                           epp_nwait,
    output wire                           reconfig,
    input  wire [IOPORTS*PORTWIDTH-1:0]   io_in,
    output wire [IOPORTS*PORTWIDTH-1:0]   io_out,
    output wire [IOPORTS*PORTWIDTH-1:0]   io_oe,
    output wire [(NUM_LEDS > 0 ? NUM_LEDS : 1)-1:0] leds
);
    wire [15:0] bus_addr;
    wire [31:0] bus_wdata, bus_rdata;
    wire        bus_we, bus_re;

    hm2_epp_bridge u_epp (
        .clk(clk_low), .rst(rst),
        .epp_d_i(epp_d_i), .epp_d_o(epp_d_o), .epp_d_oe(epp_d_oe), .epp_nwrite(epp_nwrite),
        .epp_ndatastr(epp_ndatastr), .epp_naddrstr(epp_naddrstr), .epp_nwait(epp_nwait),
        .reconfig(reconfig),
        .bus_addr(bus_addr), .bus_wdata(bus_wdata), .bus_we(bus_we), .bus_re(bus_re),
        .bus_rdata(bus_rdata)
    );

    hm2_core #(
        .IOPORTS(IOPORTS), .PORTWIDTH(PORTWIDTH), .NUM_LEDS(NUM_LEDS),
        .NUM_STEPGEN(NUM_STEPGEN), .SG_TABLE_WIDTH(SG_TABLE_WIDTH),
        .NUM_ENCODER(NUM_ENCODER), .NUM_PWMGEN(NUM_PWMGEN), .CLOCK_LOW_HZ(CLOCK_LOW_HZ),
        .WD_BASE(WD_BASE), .IO_BASE(IO_BASE), .LED_BASE(LED_BASE), .SG_BASE(SG_BASE),
        .ENC_BASE(ENC_BASE), .PWM_BASE(PWM_BASE), .NUM_XLAT(NUM_XLAT), .XLAT_BASE(XLAT_BASE),
        .NUM_SSERIAL(NUM_SSERIAL), .SS_NCHAN(SS_NCHAN), .SS_DIV(SS_DIV), .SS_BASE(SS_BASE),
        .SS_RX_SRC(SS_RX_SRC),
        .IDROM(IDROM), .ALT_SRC(ALT_SRC), .ENC_SRC(ENC_SRC),
        .ENC_PRB_SRC(ENC_PRB_SRC)
    ) u_core (
        .clk(clk_low), .clk_high(clk_high), .rst(rst),
        .bus_addr(bus_addr), .bus_wdata(bus_wdata), .bus_we(bus_we), .bus_re(bus_re),
        .bus_rdata(bus_rdata),
        .io_in(io_in), .io_out(io_out), .io_oe(io_oe), .leds(leds)
    );
endmodule

`default_nettype wire
