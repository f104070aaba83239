// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_stepgen_bank: NUM StepGen instances behind the internal register bus
// (spec §9.4, GTag 5, version 2, 10 registers, MPBitmap 0x1FF).
//
//   reg 0 Rate        W   per instance
//   reg 1 Accumulator R/W per instance (bits 47..16 of the 48-bit accumulator)
//   reg 2 Mode        W   per instance
//   reg 3 DirSetup    W   per instance
//   reg 4 DirHold     W   per instance
//   reg 5 PulseWidth  W   per instance
//   reg 6 PulseIdle   W   per instance
//   reg 7 TableData   W   per instance
//   reg 8 TableLength W   per instance
//   reg 9 Master DDS  R/W once (instance 0 address only; reads back the
//                         value written, as on Mesa's firmware)
//
// The other write-only registers read as 0, as on stock Mesa firmware.  The master DDS
// is a 32-bit phase accumulator clocked by ClockLow; its carry is the basic
// rate tick shared by all instances (power-up value 0 = all stepgens frozen).
`default_nettype none

module hm2_stepgen_bank #(
    parameter [15:0]  BASE        = 16'h2000, // MD BaseAddress
    parameter integer NUM         = 4,        // MD Instances (1..64)
    parameter integer TABLE_WIDTH = 2         // output pins per instance (2..8)
) (
    input  wire                       clk,
    input  wire                       rst,
    // Byte address; bits 1:0 are ignored by the bus convention (aligned
    // 32-bit accesses only), hence the waiver.
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [15:0]                bus_addr,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire [31:0]                bus_wdata,
    input  wire                       bus_we,
    input  wire                       bus_re,
    output reg  [31:0]                bus_rdata,
    output wire [NUM*TABLE_WIDTH-1:0] step_out
);
    localparam integer NREGS = 10;

    // Address decode: page = register, A7..A2 = instance.
    wire [7:0] page     = bus_addr[15:8];
    wire [5:0] inst     = bus_addr[7:2];
    wire [7:0] reg_off  = page - BASE[15:8];
    wire       in_range = (page >= BASE[15:8]) && (reg_off < NREGS[7:0]);
    wire       inst_ok  = ({26'd0, inst} < NUM);

    // ---- master DDS
    reg  [31:0] master_q;
    reg  [31:0] phase_q;
    reg         tick_q;
    wire [32:0] phase_sum = {1'b0, phase_q} + {1'b0, master_q};
    wire        we_master = bus_we && in_range && (reg_off == 8'd9) && (inst == 6'd0);

    always @(posedge clk) begin
        if (rst) begin
            master_q <= 32'd0;
            phase_q  <= 32'd0;
            tick_q   <= 1'b0;
        end else begin
            if (we_master) master_q <= bus_wdata;
            phase_q <= phase_sum[31:0];
            tick_q  <= phase_sum[32];
        end
    end

    // ---- instances
    wire [NUM*32-1:0] acc_rd;

    genvar i;
    generate
        for (i = 0; i < NUM; i = i + 1) begin : g_inst
            wire sel = bus_we && in_range && (inst == i[5:0]);
            hm2_stepgen #(
                .TABLE_WIDTH(TABLE_WIDTH)
            ) u_stepgen (
                .clk           (clk),
                .rst           (rst),
                .tick          (tick_q),
                .wdata         (bus_wdata),
                .we_rate       (sel && reg_off == 8'd0),
                .we_acc        (sel && reg_off == 8'd1),
                .we_mode       (sel && reg_off == 8'd2),
                .we_dirsetup   (sel && reg_off == 8'd3),
                .we_dirhold    (sel && reg_off == 8'd4),
                .we_pulsewidth (sel && reg_off == 8'd5),
                .we_pulseidle  (sel && reg_off == 8'd6),
                .we_tabledata  (sel && reg_off == 8'd7),
                .we_tablelen   (sel && reg_off == 8'd8),
                .acc_rd        (acc_rd[i*32 +: 32]),
                .out_q         (step_out[i*TABLE_WIDTH +: TABLE_WIDTH])
            );
        end
    endgenerate

    // ---- read back: the accumulators and the master DDS
    reg [31:0] rd_d;
    integer k;
    always @(*) begin
        rd_d = 32'd0;
        if (in_range && reg_off == 8'd9 && inst == 6'd0)
            rd_d = master_q;
        for (k = 0; k < NUM; k = k + 1)
            if (in_range && reg_off == 8'd1 && {26'd0, inst} == k)
                rd_d = acc_rd[k*32 +: 32];
    end

    always @(posedge clk) begin
        if (rst)
            bus_rdata <= 32'd0;
        else if (bus_re)
            bus_rdata <= inst_ok ? rd_d : 32'd0;
    end
endmodule

`default_nettype wire
