// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_encoder_bank: NUM QCounters with timestamp behind the internal
// register bus (spec §9.5, GTag 4, version 2 or 0x83 with the probe input,
// 5 registers, MPBitmap 0x03).
//
//   reg 0 Count+Timestamp R (W: clear count)  per instance
//   reg 1 Latch/Control   R/W                 per instance
//   reg 2 TSDiv           R/W  16 bit         once
//   reg 3 TSCount         R                   once
//   reg 4 QFilterRate     R/W  12 bit         once
//
// Shared prescalers: the timestamp counter advances at
// ClockLow/(TSDiv+2) (TSDiv bit 15 set: every clock), the input filters
// sample at ClockLow/(QFilterRate+2) (bit 11 set: every clock).
`default_nettype none

module hm2_encoder_bank #(
    parameter [15:0]  BASE         = 16'h3000,  // MD BaseAddress
    parameter integer NUM          = 4,         // MD Instances (1..64)
    // Only for the QFilterRate reset value (≈16 MHz sampling like Mesa's
    // firmware); the LinuxCNC driver always writes the register.
    parameter integer CLOCK_LOW_HZ = 33333333
) (
    input  wire           clk,
    input  wire           rst,
    // Byte address; bits 1:0 are ignored by the bus convention (aligned
    // 32-bit accesses only), hence the waiver.
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [15:0]    bus_addr,
    /* verilator lint_on UNUSEDSIGNAL */
    // Every encoder register is at most 16 bits wide: bits 31..16 of a
    // write are ignored (CCR bits 31..16 are the read-only latch).
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [31:0]    bus_wdata,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire           bus_we,
    input  wire           bus_re,
    output reg  [31:0]    bus_rdata,
    input  wire [NUM-1:0] enc_a,
    input  wire [NUM-1:0] enc_b,
    input  wire [NUM-1:0] enc_idx,
    input  wire [NUM-1:0] enc_idxmask,
    input  wire [NUM-1:0] enc_probe
);
    localparam integer NREGS = 5;
    localparam integer FILTER_DIV = (CLOCK_LOW_HZ + 8000000) / 16000000;
    localparam [11:0] QFILTER_RESET = (FILTER_DIV >= 2) ? FILTER_DIV[11:0] - 12'd2 : 12'hFFF;

    wire [7:0] page     = bus_addr[15:8];
    wire [5:0] inst     = bus_addr[7:2];
    wire [7:0] reg_off  = page - BASE[15:8];
    wire       in_range = (page >= BASE[15:8]) && (reg_off < NREGS[7:0]);
    wire       inst_ok  = ({26'd0, inst} < NUM);
    wire       inst0    = (inst == 6'd0);

    // ---- shared registers and prescalers
    reg  [15:0] tsdiv_q;
    reg  [15:0] tspre_q;
    reg  [15:0] tscount_q;
    reg  [11:0] qfilter_q;
    reg  [11:0] fpre_q;
    reg         sample_q;

    // Prescalers count up and tick at N+1, so a smaller divisor written
    // while one is running takes effect at once.
    wire ts_tick = tsdiv_q[15] || ({1'b0, tspre_q} >= {1'b0, tsdiv_q} + 17'd1);
    wire f_tick  = qfilter_q[11] || ({1'b0, fpre_q} >= {1'b0, qfilter_q} + 13'd1);

    always @(posedge clk) begin
        if (rst) begin
            tsdiv_q   <= 16'd0;
            tspre_q   <= 16'd0;
            tscount_q <= 16'd0;
            qfilter_q <= QFILTER_RESET;
            fpre_q    <= 12'd0;
            sample_q  <= 1'b0;
        end else begin
            if (bus_we && in_range && inst0 && reg_off == 8'd2) tsdiv_q <= bus_wdata[15:0];
            if (bus_we && in_range && inst0 && reg_off == 8'd4) qfilter_q <= bus_wdata[11:0];

            // divide by N+2: count 0 .. N+1
            if (ts_tick) begin
                tspre_q   <= 16'd0;
                tscount_q <= tscount_q + 16'd1;
            end else begin
                tspre_q <= tspre_q + 16'd1;
            end

            sample_q <= f_tick;
            if (f_tick)
                fpre_q <= 12'd0;
            else
                fpre_q <= fpre_q + 12'd1;
        end
    end

    // ---- instances
    wire [NUM*32-1:0] count_rd;
    wire [NUM*32-1:0] ccr_rd;

    genvar i;
    generate
        for (i = 0; i < NUM; i = i + 1) begin : g_inst
            wire sel = bus_we && in_range && (inst == i[5:0]);
            hm2_encoder u_encoder (
                .clk      (clk),
                .rst      (rst),
                .sample   (sample_q),
                .ts_count (tscount_q),
                .wdata    (bus_wdata[15:3]),
                .we_count (sel && reg_off == 8'd0),
                .we_ccr   (sel && reg_off == 8'd1),
                .a_pin    (enc_a[i]),
                .b_pin    (enc_b[i]),
                .idx_pin  (enc_idx[i]),
                .mask_pin (enc_idxmask[i]),
                .probe_pin(enc_probe[i]),
                .count_rd (count_rd[i*32 +: 32]),
                .ccr_rd   (ccr_rd[i*32 +: 32])
            );
        end
    endgenerate

    // ---- read back
    reg [31:0] rd_d;
    integer k;
    always @(*) begin
        rd_d = 32'd0;
        if (in_range) begin
            case (reg_off)
                8'd0, 8'd1: begin
                    for (k = 0; k < NUM; k = k + 1)
                        if ({26'd0, inst} == k)
                            rd_d = (reg_off == 8'd0) ? count_rd[k*32 +: 32] : ccr_rd[k*32 +: 32];
                end
                8'd2: if (inst0) rd_d = {16'd0, tsdiv_q};
                8'd3: if (inst0) rd_d = {16'd0, tscount_q};
                8'd4: if (inst0) rd_d = {20'd0, qfilter_q};
                default: rd_d = 32'd0;
            endcase
        end
    end

    always @(posedge clk) begin
        if (rst)
            bus_rdata <= 32'd0;
        else if (bus_re)
            bus_rdata <= inst_ok ? rd_d : 32'd0;
    end
endmodule

`default_nettype wire
