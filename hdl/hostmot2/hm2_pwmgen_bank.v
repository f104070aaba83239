// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_pwmgen_bank: NUM PWM generators behind the internal register bus
// (spec §9.6, GTag 6, version 0, 5 registers, MPBitmap 0x03, ClockHigh).
//
//   reg 0 PWMVal   W  per instance: bit 31 DIR, bits 27..16 value
//   reg 1 Mode     W  per instance: bits 1..0 resolution 9..12, bit 2
//                     symmetric, bits 4..3 output mode, bit 5 double buffer
//   reg 2 PWM rate W  once: PWMCLK = ClockHigh * rate / 65536
//   reg 3 PDM rate W  once: PDMCLK = ClockHigh * rate / 65536
//   reg 4 Enable   RW once: bit n = 1 drives instance n's Not-Enable low
//
// Registers live in the ClockLow bus domain.  Value, mode and rates cross
// into ClockHigh as one snapshot through a toggle request/acknowledge
// handshake (2-FF synchronizers both ways): the snapshot register is only
// reloaded after the ClockHigh side acknowledged the previous one, so the
// multi-bit data is always stable when the other domain samples it.  Writes
// arriving during a transfer are sent in the next one.  Enable drives a
// static level and stays in ClockLow.
`default_nettype none

module hm2_pwmgen_bank #(
    parameter [15:0]  BASE = 16'h4000,  // MD BaseAddress
    parameter integer NUM  = 4          // MD Instances (1..32)
) (
    input  wire           clk,          // ClockLow: bus
    input  wire           clk_high,     // ClockHigh: PWM/PDM
    input  wire           rst,          // synchronous to clk
    // Byte address; bits 1:0 are ignored by the bus convention (aligned
    // 32-bit accesses only), hence the waiver.
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [15:0]    bus_addr,
    // PWMVal bits 30..28 and 15..0 (dither fraction, v1 only) are ignored.
    input  wire [31:0]    bus_wdata,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire           bus_we,
    input  wire           bus_re,
    output reg  [31:0]    bus_rdata,
    output wire [NUM-1:0] pwm_out0,
    output wire [NUM-1:0] pwm_out1,
    output reg  [NUM-1:0] pwm_nenable
);
    localparam integer NREGS = 5;
    localparam integer XW = NUM * 13 + NUM * 6 + 32;  // snapshot width

    wire [7:0] page     = bus_addr[15:8];
    wire [5:0] inst     = bus_addr[7:2];
    wire [7:0] reg_off  = page - BASE[15:8];
    wire       in_range = (page >= BASE[15:8]) && (reg_off < NREGS[7:0]);
    wire       inst_ok  = ({26'd0, inst} < NUM);
    wire       inst0    = (inst == 6'd0);

    // ================= ClockLow side =================
    reg  [NUM*13-1:0] val_q;
    reg  [NUM*6-1:0]  mode_q;
    reg  [15:0]       pwmrate_q;
    reg  [15:0]       pdmrate_q;
    reg  [NUM-1:0]    enable_q;
    reg               dirty_q;
    reg               busy_q;
    reg               req_q;
    reg  [XW-1:0]     xfer_q;
    wire              ack_s;

    wire wr_val  = bus_we && in_range && inst_ok && reg_off == 8'd0;
    wire wr_mode = bus_we && in_range && inst_ok && reg_off == 8'd1;
    wire wr_pwmr = bus_we && in_range && inst0 && reg_off == 8'd2;
    wire wr_pdmr = bus_we && in_range && inst0 && reg_off == 8'd3;
    wire wr_en   = bus_we && in_range && inst0 && reg_off == 8'd4;
    wire start   = dirty_q && !busy_q;

    integer n;
    always @(posedge clk) begin
        if (rst) begin
            val_q       <= {NUM*13{1'b0}};
            mode_q      <= {NUM*6{1'b0}};
            pwmrate_q   <= 16'd0;
            pdmrate_q   <= 16'd0;
            enable_q    <= {NUM{1'b0}};
            pwm_nenable <= {NUM{1'b1}};
            dirty_q     <= 1'b0;
            busy_q      <= 1'b1;   // until the ClockHigh side shows its reset
            req_q       <= 1'b0;
            xfer_q      <= {XW{1'b0}};
        end else begin
            for (n = 0; n < NUM; n = n + 1) begin
                if (wr_val && {26'd0, inst} == n)
                    val_q[n*13 +: 13] <= {bus_wdata[31], bus_wdata[27:16]};
                if (wr_mode && {26'd0, inst} == n)
                    mode_q[n*6 +: 6] <= bus_wdata[5:0];
            end
            if (wr_pwmr) pwmrate_q <= bus_wdata[15:0];
            if (wr_pdmr) pdmrate_q <= bus_wdata[15:0];
            if (wr_en)   enable_q  <= bus_wdata[NUM-1:0];
            pwm_nenable <= ~enable_q;

            if (start) begin
                xfer_q <= {pdmrate_q, pwmrate_q, mode_q, val_q};
                req_q  <= ~req_q;
                busy_q <= 1'b1;
            end else if (busy_q && ack_s == req_q) begin
                busy_q <= 1'b0;
            end
            dirty_q <= (dirty_q && !start) || wr_val || wr_mode || wr_pwmr || wr_pdmr;
        end
    end

    reg [31:0] rd_d;
    always @(*) begin
        rd_d = 32'd0;
        if (in_range && inst0 && reg_off == 8'd4)
            rd_d[NUM-1:0] = enable_q;
    end

    always @(posedge clk) begin
        if (rst)
            bus_rdata <= 32'd0;
        else if (bus_re)
            bus_rdata <= rd_d;
    end

    // ================= ClockHigh side =================
    wire rst_h;
    wire req_s;
    reg  ack_h_q;
    reg  [XW-1:0] cfg_h_q;

    // ClockLow's synchronous reset, brought into ClockHigh.
    sync_ff #(.WIDTH(1), .STAGES(2), .RESET_VALUE(1'b1)) u_rst_sync (
        .clk(clk_high), .rst(1'b0), .d(rst), .q(rst_h)
    );
    sync_ff #(.WIDTH(1), .STAGES(2)) u_req_sync (
        .clk(clk_high), .rst(rst_h), .d(req_q), .q(req_s)
    );
    sync_ff #(.WIDTH(1), .STAGES(2)) u_ack_sync (
        .clk(clk), .rst(1'b0), .d(ack_h_q), .q(ack_s)
    );

    always @(posedge clk_high) begin
        if (rst_h) begin
            ack_h_q <= 1'b0;
            cfg_h_q <= {XW{1'b0}};
        end else if (req_s != ack_h_q) begin
            cfg_h_q <= xfer_q;   // stable: ClockLow holds it until acknowledged
            ack_h_q <= req_s;
        end
    end

    wire [NUM*13-1:0] val_h     = cfg_h_q[NUM*13-1:0];
    wire [NUM*6-1:0]  mode_h    = cfg_h_q[NUM*19-1:NUM*13];
    wire [15:0]       pwmrate_h = cfg_h_q[NUM*19 +: 16];
    wire [15:0]       pdmrate_h = cfg_h_q[NUM*19+16 +: 16];

    // rate DDSs and the shared reference counter
    reg  [15:0] pwm_phase_q;
    reg  [15:0] pdm_phase_q;
    reg         pwm_tick_q;
    reg         pdm_tick_q;
    reg  [12:0] ref_q;
    wire [16:0] pwm_sum = {1'b0, pwm_phase_q} + {1'b0, pwmrate_h};
    wire [16:0] pdm_sum = {1'b0, pdm_phase_q} + {1'b0, pdmrate_h};

    always @(posedge clk_high) begin
        if (rst_h) begin
            pwm_phase_q <= 16'd0;
            pdm_phase_q <= 16'd0;
            pwm_tick_q  <= 1'b0;
            pdm_tick_q  <= 1'b0;
            ref_q       <= 13'd0;
        end else begin
            pwm_phase_q <= pwm_sum[15:0];
            pdm_phase_q <= pdm_sum[15:0];
            pwm_tick_q  <= pwm_sum[16];
            pdm_tick_q  <= pdm_sum[16];
            if (pwm_tick_q) ref_q <= ref_q + 13'd1;
        end
    end

    genvar i;
    generate
        for (i = 0; i < NUM; i = i + 1) begin : g_inst
            hm2_pwmgen u_pwmgen (
                .clk_high (clk_high),
                .rst      (rst_h),
                .val      (val_h[i*13 +: 13]),
                .mode     (mode_h[i*6 +: 6]),
                .ref_cnt  (ref_q),
                .pwm_tick (pwm_tick_q),
                .pdm_tick (pdm_tick_q),
                .out0_q   (pwm_out0[i]),
                .out1_q   (pwm_out1[i])
            );
        end
    endgenerate
endmodule

`default_nettype wire
