// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_stepgen: one HostMot2 StepGen (v2 register semantics, spec §9.4, plus
// the swap step/dir bit of version 0x42: Mode bit 2 exchanges output pins 0
// and 1 in every output mode).
//
// The bank (hm2_stepgen_bank) decodes the bus and hands this core one write
// strobe per register plus the shared basic-rate tick of the master DDS.
//
// Motion: a 48-bit accumulator (16 integer step bits . 32 fraction bits)
// adds the sign-extended 32-bit Rate on every tick.  A step is an integer
// boundary crossing (bit 32 toggles; |Rate| < 2^32 moves at most one step per
// tick).  Quadrature mode emits a Gray state change on every quarter-step
// crossing (bit 30), table mode advances the table pointer on every step.
//
// Timing is guaranteed by construction: when an add would produce an output
// event that is not allowed yet, the add is dropped for that tick (the
// position simply arrives later, and the host's position loop sees it in the
// accumulator read-back).  Rules, all in ClockLow periods:
//   - a step pulse is high exactly PulseWidth+1 clocks;
//   - the next step rises at least PulseIdle+1 clocks after the fall;
//   - DIR changes at least DirHold+1 clocks after the last step fell;
//   - a step rises at least DirSetup+1 clocks after the last DIR change.
// In quadrature and table modes each output state lasts at least
// PulseWidth+1+PulseIdle+1 clocks (there is no DIR pin to set up).
//
// All outputs are registered (one clock after the internal state) so the
// pins never glitch.
`default_nettype none

module hm2_stepgen #(
    // Output pins per instance: 0 Step, 1 Dir, 2.. table bits 2..
    parameter integer TABLE_WIDTH = 2
) (
    input  wire                   clk,
    input  wire                   rst,
    input  wire                   tick,       // basic-rate tick (master DDS carry)
    input  wire [31:0]            wdata,
    input  wire                   we_rate,
    input  wire                   we_acc,
    input  wire                   we_mode,
    input  wire                   we_dirsetup,
    input  wire                   we_dirhold,
    input  wire                   we_pulsewidth,
    input  wire                   we_pulseidle,
    input  wire                   we_tabledata,
    input  wire                   we_tablelen,
    output wire [31:0]            acc_rd,     // accumulator bits 47..16 (16.16)
    output reg  [TABLE_WIDTH-1:0] out_q
);
    localparam integer TW = TABLE_WIDTH;
    localparam [1:0] MODE_STEPDIR = 2'd0;
    localparam [1:0] MODE_UPDOWN  = 2'd1;
    localparam [1:0] MODE_QUAD    = 2'd2;
    localparam [1:0] MODE_TABLE   = 2'd3;
    // Quadrature moves at most one Gray state per tick: |rate| is limited to
    // a quarter step there.
    localparam [31:0] QUARTER_POS = 32'h4000_0000;
    localparam [31:0] QUARTER_NEG = 32'hC000_0000;

    // ---- host registers
    reg [31:0]        rate_q;
    reg [47:0]        acc_q;
    reg [1:0]         mode_q;
    reg               swap_q;      // Mode bit 2: swap Step and Dir pins
    reg [13:0]        dirsetup_q;
    reg [13:0]        dirhold_q;
    reg [13:0]        pulsewidth_q;
    reg [13:0]        pulseidle_q;
    reg [16*TW-1:0]   table_q;     // entry e at [e*TW +: TW]
    reg [3:0]         tablelen_q;  // sequence length - 1

    // ---- motion state
    reg               pulse_q;     // step pulse (or event period) active
    reg               dir_q;       // 1 = negative
    reg [13:0]        width_cnt_q;
    reg [13:0]        idle_cnt_q;
    reg [13:0]        hold_cnt_q;
    reg [13:0]        setup_cnt_q;
    reg [3:0]         ptr_q;

    wire              neg = rate_q[31];
    wire              seq_mode = mode_q[1];   // quadrature or table: no DIR pin

    reg  [31:0]       rate_eff;
    always @(*) begin
        rate_eff = rate_q;
        if (mode_q == MODE_QUAD) begin
            if (!neg && rate_q > QUARTER_POS)
                rate_eff = QUARTER_POS;
            else if (neg && rate_q < QUARTER_NEG)
                rate_eff = QUARTER_NEG;
        end
    end

    wire [47:0] sum = acc_q + {{16{rate_eff[31]}}, rate_eff};
    wire        crosses = (mode_q == MODE_QUAD) ? (sum[30] ^ acc_q[30]) : (sum[32] ^ acc_q[32]);
    wire        event_ok = !pulse_q && (idle_cnt_q == 14'd0) &&
                           (seq_mode || ((dir_q == neg) && (setup_cnt_q == 14'd0)));
    wire        do_event = tick && crosses && event_ok;
    wire        do_add   = tick && (!crosses || event_ok);
    wire        dir_change = (neg != dir_q) && !pulse_q && (hold_cnt_q == 14'd0);

    assign acc_rd = acc_q[47:16];

    // ---- host register writes
    always @(posedge clk) begin
        if (rst) begin
            rate_q       <= 32'd0;
            mode_q       <= MODE_STEPDIR;
            swap_q       <= 1'b0;
            dirsetup_q   <= 14'd0;
            dirhold_q    <= 14'd0;
            pulsewidth_q <= 14'd0;
            pulseidle_q  <= 14'd0;
            table_q      <= {16*TW{1'b0}};
            tablelen_q   <= 4'd0;
        end else begin
            if (we_rate)       rate_q       <= wdata;
            if (we_mode)       mode_q       <= wdata[1:0];
            if (we_mode)       swap_q       <= wdata[2];
            if (we_dirsetup)   dirsetup_q   <= wdata[13:0];
            if (we_dirhold)    dirhold_q    <= wdata[13:0];
            if (we_pulsewidth) pulsewidth_q <= wdata[13:0];
            if (we_pulseidle)  pulseidle_q  <= wdata[13:0];
            // Shift register: entries are written last first, so the most
            // recent write ends up as entry 0.
            if (we_tabledata)  table_q      <= {table_q[15*TW-1:0], wdata[TW-1:0]};
            if (we_tablelen)   tablelen_q   <= wdata[3:0];
        end
    end

    // ---- accumulator, pulse timing, direction, table pointer
    always @(posedge clk) begin
        if (rst) begin
            acc_q       <= 48'd0;
            pulse_q     <= 1'b0;
            dir_q       <= 1'b0;
            width_cnt_q <= 14'd0;
            idle_cnt_q  <= 14'd0;
            hold_cnt_q  <= 14'd0;
            setup_cnt_q <= 14'd0;
            ptr_q       <= 4'd0;
        end else begin
            if (we_acc)
                acc_q <= {wdata, 16'h0000};
            else if (do_add)
                acc_q <= sum;

            if (do_event) begin
                pulse_q     <= 1'b1;
                width_cnt_q <= pulsewidth_q;
            end else if (pulse_q) begin
                if (width_cnt_q == 14'd0) begin
                    pulse_q    <= 1'b0;
                    idle_cnt_q <= pulseidle_q;
                    hold_cnt_q <= dirhold_q;
                end else begin
                    width_cnt_q <= width_cnt_q - 14'd1;
                end
            end else begin
                if (idle_cnt_q != 14'd0) idle_cnt_q <= idle_cnt_q - 14'd1;
                if (hold_cnt_q != 14'd0) hold_cnt_q <= hold_cnt_q - 14'd1;
            end

            if (dir_change) begin
                dir_q       <= neg;
                setup_cnt_q <= dirsetup_q;
            end else if (setup_cnt_q != 14'd0) begin
                setup_cnt_q <= setup_cnt_q - 14'd1;
            end

            if (we_tablelen)
                ptr_q <= 4'd0;
            else if (do_event && mode_q == MODE_TABLE) begin
                if (!neg)
                    ptr_q <= (ptr_q == tablelen_q) ? 4'd0 : ptr_q + 4'd1;
                else
                    ptr_q <= (ptr_q == 4'd0) ? tablelen_q : ptr_q - 4'd1;
            end
        end
    end

    // ---- output formatting
    reg [TW-1:0] out_d;
    always @(*) begin
        out_d = {TW{1'b0}};
        case (mode_q)
            MODE_STEPDIR: begin
                out_d[0] = pulse_q;
                out_d[1] = dir_q;
            end
            MODE_UPDOWN: begin
                out_d[0] = pulse_q & ~dir_q;
                out_d[1] = pulse_q & dir_q;
            end
            MODE_QUAD: begin
                out_d[0] = acc_q[31] ^ acc_q[30];
                out_d[1] = acc_q[31];
            end
            default: out_d = table_q[ptr_q*TW +: TW];
        endcase
        if (swap_q)
            out_d[1:0] = {out_d[0], out_d[1]};
    end

    always @(posedge clk) begin
        if (rst)
            out_q <= {TW{1'b0}};
        else
            out_q <= out_d;
    end
endmodule

`default_nettype wire
