// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_pwmgen: the ClockHigh part of one HostMot2 PWMGen (spec §9.6, v0).
//
// The bank hands over, already in this clock domain: the value (12-bit
// magnitude + DIR bit 31), the mode word, the shared 13-bit reference
// counter with its PWMCLK tick and the PDMCLK tick.
//
// PWM: sawtooth compares the reference counter masked to `bits`
// (9..12) with the value; symmetric (mode bit 2) folds a `bits+1` counter
// into a triangle.  Output high while reference < value, so a value of
// 2^bits or more is 100 %.  Double buffering (mode bit 5) loads value and
// DIR only when this instance's PWM cycle starts.
// PDM: each PDMCLK tick adds the 12-bit value to a 12-bit accumulator; the
// carry is the output for that slot (density value/4096).
// Output modes (bits 4..3): 00 PWM/DIR, 01 DIR/PWM, 10 up/down (Out0 pulses
// when DIR = 1, as in Mesa's VHDL, spec §20), 11 PDM/DIR.
`default_nettype none

module hm2_pwmgen (
    input  wire        clk_high,
    input  wire        rst,        // synchronous to clk_high
    input  wire [12:0] val,        // {DIR, value[11:0]}
    input  wire [5:0]  mode,
    input  wire [12:0] ref_cnt,    // shared reference counter (value before tick)
    input  wire        pwm_tick,
    input  wire        pdm_tick,
    output reg         out0_q,
    output reg         out1_q
);
    reg  [12:0] act_q;        // value in use {DIR, value}
    reg  [11:0] pdm_acc_q;
    reg         pdm_q;
    reg         pwm_q;
    reg         dir_q;        // DIR aligned with pwm_q

    wire [1:0]  res = mode[1:0];
    wire        sym = mode[2];
    wire [1:0]  omode = mode[4:3];
    wire        dbuf = mode[5];

    // reference masked to the resolution (+1 bit when symmetric)
    reg  [12:0] span;         // 2^bits - 1 (sawtooth) or 2^(bits+1) - 1 (symmetric)
    always @(*) begin
        case ({sym, res})
            3'b000: span = 13'h01FF;
            3'b001: span = 13'h03FF;
            3'b010: span = 13'h07FF;
            3'b011: span = 13'h0FFF;
            3'b100: span = 13'h03FF;
            3'b101: span = 13'h07FF;
            3'b110: span = 13'h0FFF;
            default: span = 13'h1FFF;
        endcase
    end

    wire [12:0] ref_m = ref_cnt & span;
    wire [12:0] half = {1'b0, span[12:1]};        // 2^bits - 1 when symmetric
    // triangle: up 0..M, then down M..0 (M = 2^bits - 1)
    wire [12:0] tri_ref = (ref_m > half) ? (span - ref_m) : ref_m;
    wire [12:0] cmp = sym ? tri_ref : ref_m;
    // the cycle starts when the masked reference wraps to 0
    wire        cycle_start = pwm_tick && (ref_m == span);

    wire [12:0] pdm_sum = {1'b0, pdm_acc_q} + {1'b0, act_q[11:0]};

    always @(posedge clk_high) begin
        if (rst) begin
            act_q     <= 13'd0;
            pdm_acc_q <= 12'd0;
            pdm_q     <= 1'b0;
            pwm_q     <= 1'b0;
            dir_q     <= 1'b0;
            out0_q    <= 1'b0;
            out1_q    <= 1'b0;
        end else begin
            if (!dbuf || cycle_start)
                act_q <= val;
            pwm_q <= (cmp < {1'b0, act_q[11:0]});
            dir_q <= act_q[12];
            if (pdm_tick) begin
                pdm_acc_q <= pdm_sum[11:0];
                pdm_q     <= pdm_sum[12];
            end
            case (omode)
                2'b00: begin out0_q <= pwm_q;          out1_q <= dir_q;          end
                2'b01: begin out0_q <= dir_q;          out1_q <= pwm_q;          end
                2'b10: begin out0_q <= pwm_q & dir_q;  out1_q <= pwm_q & ~dir_q; end
                default: begin out0_q <= pdm_q;        out1_q <= dir_q;          end
            endcase
        end
    end
endmodule

`default_nettype wire
