// SPDX-License-Identifier: GPL-2.0-or-later
//
// pluto_pwm: one pluto_servo PWM channel.
//
// word (the host's 16-bit register): bits 10..0 duty, 12 UP xor, 13 DN xor,
// 15 sign (0: pulses on UP, 1: pulses on DN).  The channel is active while
// duty > compare, so duty 0 is off and 2047 always on.  compare is the
// shared period counter, or in PDM mode the counter with bits 10..4
// reversed (compare[10] = cnt[4] ... compare[4] = cnt[10], bits 3..0 kept),
// which spreads the on-time over the period in 16-clock slots.
// Outputs are registered (one clock after the counter).
`default_nettype none

module pluto_pwm (
    input  wire        clk,
    input  wire        rst,
    input  wire [10:0] cnt,
    input  wire        pdm,
    input  wire [15:0] word,
    output reg         up_q,
    output reg         dn_q
);
    wire [10:0] scrambled = {cnt[4], cnt[5], cnt[6], cnt[7], cnt[8], cnt[9], cnt[10], cnt[3:0]};
    wire [10:0] cmp = pdm ? scrambled : cnt;
    // duty > cmp is the carry out of duty + ~cmp (a bare carry chain).
    wire [10:0] sum_unused;
    wire        active;
    assign {active, sum_unused} = {1'b0, word[10:0]} + {1'b0, ~cmp};

    always @(posedge clk or posedge rst) begin
        if (rst) begin
            up_q <= 1'b0;
            dn_q <= 1'b0;
        end else begin
            up_q <= word[12] ^ (~word[15] & active);
            dn_q <= word[13] ^ (word[15] & active);
        end
    end

    // word[11] and word[14] (PDM select, taken from channel 0 by the top)
    // are not this channel's business.
    wire unused_ok = &{1'b0, word[11], word[14]};
endmodule

`default_nettype wire
