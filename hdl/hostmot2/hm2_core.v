// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_core: the generic HostMot2 core behind any host bus front end.  One
// firmware = this core + the parameters that tools/hm2gen computes from the
// firmware description (the generated <top>_inc.v), so the address decode,
// the pin routing and the IDROM all come from the same description.
//
// Contents: ID block + IDROM (hm2_idrom), watchdog, IOPorts, LED register
// (if NUM_LEDS > 0), StepGen / Encoder / PWMGen banks (if their count > 0)
// and the pin router.  Every module decodes its own addresses from its MD
// base address; bus_rdata is the OR of all modules' read data (each returns
// 0 for reads not addressed to it).  clk is ClockLow; clk_high (ClockHigh)
// goes only to the PWMGen bank, which does its own clock-domain crossing.
//
// Parameters:
//   IOPORTS, PORTWIDTH   connectors and pins per connector (IOWidth = product)
//   NUM_LEDS             LEDs of the board (0 = no LED module)
//   NUM_STEPGEN, SG_TABLE_WIDTH, NUM_ENCODER, NUM_PWMGEN   module counts
//   CLOCK_LOW_HZ         ClockLow in Hz (IDROM value; encoder filter reset value)
//   NUM_XLAT             1 = EPP translation RAM (hm2_xlat_ram) present
//   NUM_SSERIAL, SS_NCHAN, SS_DIV   Smart Serial ports, channels per port,
//                        ClockLow periods per bit
//   SS_RX_SRC            per Smart Serial channel: pin+1 of RxData (0 = none)
//   *_BASE               MD base addresses
//   IDROM                IDROM image, word k in bits 32k+31..32k
//   ALT_SRC              per pin, 16 bits: index into mod_out (0 = none)
//   ENC_SRC              per encoder, 4 x 16 bits: pin+1 of A, B, Index,
//                        IndexMask (0 = tied low)
//   ENC_PRB_SRC          per encoder, 16 bits: pin+1 of Probe (0 = tied low)
//
// mod_out layout (also what hm2gen assumes): bit 0 = constant 0, then
// step_out (instance i, bit k at 1 + i*SG_TABLE_WIDTH + k), then PWM Out0
// of every instance, Out1 of every instance, NotEnable of every instance,
// then the Smart Serial TxData of every channel (port p, channel c at
// p*SS_NCHAN + c).
`default_nettype none

module hm2_core #(
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
    input  wire                           clk,
    // Only the PWMGen bank uses ClockHigh.
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire                           clk_high,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire                           rst,
    input  wire [15:0]                    bus_addr,
    input  wire [31:0]                    bus_wdata,
    input  wire                           bus_we,
    input  wire                           bus_re,
    output wire [31:0]                    bus_rdata,
    input  wire [IOPORTS*PORTWIDTH-1:0]   io_in,
    output wire [IOPORTS*PORTWIDTH-1:0]   io_out,
    output wire [IOPORTS*PORTWIDTH-1:0]   io_oe,
    output wire [(NUM_LEDS > 0 ? NUM_LEDS : 1)-1:0] leds
);
    localparam integer IOW  = IOPORTS * PORTWIDTH;
    localparam integer NENC = NUM_ENCODER > 0 ? NUM_ENCODER : 1;
    localparam integer SGW  = NUM_STEPGEN * SG_TABLE_WIDTH;
    localparam integer NSSC = NUM_SSERIAL * SS_NCHAN;
    localparam integer NSS  = NSSC > 0 ? NSSC : 1;
    localparam integer MODW = 1 + SGW + 3 * NUM_PWMGEN + NSSC;

    wire [31:0] rd_idrom, rd_wd, rd_io;
    wire        bite;
    wire [IOW-1:0] alt_out;
    wire [MODW-1:0] mod_out;
    wire [NENC-1:0] enc_a, enc_b, enc_idx, enc_idxmask, enc_probe;
    wire [NSS-1:0]  ss_rx;

    assign mod_out[0] = 1'b0;

    hm2_idrom #(.IDROM(IDROM)) u_idrom (
        .clk(clk), .rst(rst), .bus_addr(bus_addr), .bus_wdata(bus_wdata), .bus_we(bus_we),
        .bus_re(bus_re), .bus_rdata(rd_idrom)
    );

    hm2_watchdog #(.BASE(WD_BASE)) u_wd (
        .clk(clk), .rst(rst), .bus_addr(bus_addr), .bus_wdata(bus_wdata), .bus_we(bus_we),
        .bus_re(bus_re), .bus_rdata(rd_wd), .bite(bite)
    );

    // The pin levels are read through the IOPort Data register only.
    /* verilator lint_off UNUSEDSIGNAL */
    wire [IOW-1:0] pin_level;
    /* verilator lint_on UNUSEDSIGNAL */
    hm2_ioport_bank #(.BASE(IO_BASE), .NPORTS(IOPORTS), .PORTWIDTH(PORTWIDTH)) u_io (
        .clk(clk), .rst(rst), .bus_addr(bus_addr), .bus_wdata(bus_wdata), .bus_we(bus_we),
        .bus_re(bus_re), .bus_rdata(rd_io), .bite(bite), .io_in(io_in), .alt_out(alt_out),
        .io_out(io_out), .io_oe(io_oe), .pin_level(pin_level)
    );

    generate
        if (NUM_LEDS > 0) begin : g_led
            hm2_led #(.BASE(LED_BASE), .NUM_LEDS(NUM_LEDS)) u_led (
                .clk(clk), .rst(rst), .bus_addr(bus_addr), .bus_wdata(bus_wdata),
                .bus_we(bus_we), .leds(leds)
            );
        end else begin : g_noled
            assign leds = 1'b0;
        end
    endgenerate

    wire [31:0] rd_sg, rd_enc, rd_pwm, rd_xlat, rd_ss;
    generate
        if (NSSC > 0) begin : g_ss
            wire [NSSC-1:0] ss_tx;
            hm2_sserial #(.BASE(SS_BASE), .NUM(NUM_SSERIAL), .NCHAN(SS_NCHAN), .DIV(SS_DIV)) u_ss (
                .clk(clk), .rst(rst), .bus_addr(bus_addr), .bus_wdata(bus_wdata),
                .bus_we(bus_we), .bus_re(bus_re), .bus_rdata(rd_ss), .tx(ss_tx), .rx(ss_rx)
            );
            assign mod_out[1 + SGW + 3*NUM_PWMGEN +: NSSC] = ss_tx;
        end else begin : g_noss
            assign rd_ss = 32'd0;
            // no channel: the router's idle-line input is not read
            /* verilator lint_off UNUSEDSIGNAL */
            wire ss_unused = &ss_rx;
            /* verilator lint_on UNUSEDSIGNAL */
        end
        if (NUM_XLAT > 0) begin : g_xlat
            hm2_xlat_ram #(.BASE(XLAT_BASE)) u_xlat (
                .clk(clk), .rst(rst), .bus_addr(bus_addr), .bus_wdata(bus_wdata),
                .bus_we(bus_we), .bus_re(bus_re), .bus_rdata(rd_xlat)
            );
        end else begin : g_noxlat
            assign rd_xlat = 32'd0;
        end

        if (NUM_STEPGEN > 0) begin : g_sg
            wire [SGW-1:0] step_out;
            hm2_stepgen_bank #(.BASE(SG_BASE), .NUM(NUM_STEPGEN), .TABLE_WIDTH(SG_TABLE_WIDTH)) u_sg (
                .clk(clk), .rst(rst), .bus_addr(bus_addr), .bus_wdata(bus_wdata),
                .bus_we(bus_we), .bus_re(bus_re), .bus_rdata(rd_sg), .step_out(step_out)
            );
            assign mod_out[1 +: SGW] = step_out;
        end else begin : g_nosg
            assign rd_sg = 32'd0;
        end

        if (NUM_ENCODER > 0) begin : g_enc
            hm2_encoder_bank #(.BASE(ENC_BASE), .NUM(NUM_ENCODER), .CLOCK_LOW_HZ(CLOCK_LOW_HZ)) u_enc (
                .clk(clk), .rst(rst), .bus_addr(bus_addr), .bus_wdata(bus_wdata),
                .bus_we(bus_we), .bus_re(bus_re), .bus_rdata(rd_enc),
                .enc_a(enc_a), .enc_b(enc_b), .enc_idx(enc_idx), .enc_idxmask(enc_idxmask),
                .enc_probe(enc_probe)
            );
        end else begin : g_noenc
            assign rd_enc = 32'd0;
        end

        if (NUM_PWMGEN > 0) begin : g_pwm
            wire [NUM_PWMGEN-1:0] pwm_out0, pwm_out1, pwm_nenable;
            hm2_pwmgen_bank #(.BASE(PWM_BASE), .NUM(NUM_PWMGEN)) u_pwm (
                .clk(clk), .clk_high(clk_high), .rst(rst), .bus_addr(bus_addr),
                .bus_wdata(bus_wdata), .bus_we(bus_we), .bus_re(bus_re), .bus_rdata(rd_pwm),
                .pwm_out0(pwm_out0), .pwm_out1(pwm_out1), .pwm_nenable(pwm_nenable)
            );
            assign mod_out[1 + SGW +: 3*NUM_PWMGEN] = {pwm_nenable, pwm_out1, pwm_out0};
        end else begin : g_nopwm
            assign rd_pwm = 32'd0;
        end
    endgenerate

    // Encoder inputs are unused when the firmware has no encoder.
    /* verilator lint_off UNUSEDSIGNAL */
    wire [NENC-1:0] enc_unused = enc_a & enc_b & enc_idx & enc_idxmask & enc_probe;
    /* verilator lint_on UNUSEDSIGNAL */

    hm2_pin_router #(
        .IOWIDTH(IOW), .MODW(MODW), .NENC(NENC), .ALT_SRC(ALT_SRC), .ENC_SRC(ENC_SRC),
        .ENC_PRB_SRC(ENC_PRB_SRC), .NSS(NSS), .SS_RX_SRC(SS_RX_SRC)
    ) u_router (
        .mod_out(mod_out), .io_in(io_in), .alt_out(alt_out),
        .enc_a(enc_a), .enc_b(enc_b), .enc_idx(enc_idx), .enc_idxmask(enc_idxmask),
        .enc_probe(enc_probe), .ss_rx(ss_rx)
    );

    assign bus_rdata = rd_idrom | rd_wd | rd_io | rd_sg | rd_enc | rd_pwm | rd_xlat | rd_ss;
endmodule

`default_nettype wire
