// SPDX-License-Identifier: GPL-2.0-or-later
//
// pluto_stepgen: one pluto_step step/direction generator.
//
// Everything happens on tick (every 64 clocks = 1.6 us at 40 MHz):
//  - the position accumulator (W.F fixed point, wrapping) adds the signed
//    velocity (F+1 bits, units 2^-F step per tick) while DIR agrees with the
//    velocity's sign;
//  - a step is due when the selected position bit (F + tap) differs from
//    the value it had at the last step; then STEP goes high for
//    steptime+1 ticks and low for at least 1 tick before the next step
//    (step space is the driver's business, as in the original);
//  - when the velocity's sign differs from DIR and no step is due, the
//    accumulator stops, STEP is let fall, DIR changes dirtime+1 ticks after
//    the fall (hold) and the next step comes no earlier than dirtime+1 ticks
//    after the DIR change (setup).
// So |velocity| = 2^(F-1) (1024) gives one step per 2 ticks, 312.5 kHz at
// tap 0, the top rate; faster velocities lose steps.  DIR = 1 while the
// velocity is negative.  Changing tap may give one extra step.
`default_nettype none

module pluto_stepgen #(
    parameter integer W = 10,
    parameter integer F = 11,
    parameter integer T = 4
) (
    input  wire           clk,
    input  wire           rst,
    input  wire           tick,
    input  wire [F:0]     vel,
    input  wire [T-1:0]   steptime,
    input  wire [T-1:0]   dirtime,
    input  wire [1:0]     tap,
    output wire [W+F-1:0] pos,
    output reg            step_q,
    output reg            dir_q
);
    // Phase, one bit per wait: hold_q (DIR hold before the change) and
    // setup_q (DIR setup after it); neither = RUN.  One timer serves the
    // STEP high time in RUN and the hold / setup time: HOLD is entered only
    // with the step timer at 0, RUN only with the wait timer at 0.
    reg [W+F-1:0] pos_q;
    reg [T-1:0]   timer_q;
    reg           hold_q;
    reg           setup_q;
    reg           last_q;

    wire           vsign   = vel[F];
    wire [3:0]     taps    = pos_q[F+3:F];
    wire           due     = taps[tap] ^ last_q;
    wire           turn    = vsign ^ dir_q;
    wire           idle    = (timer_q == {T{1'b0}});
    wire           run     = ~hold_q & (~setup_q | idle);
    wire           act     = ~hold_q & idle;  // run with the timer at 0
    wire           ld_step = act & ~step_q & due;
    wire           ld_dir  = idle & turn & (hold_q | ~due);
    wire [W+F-1:0] vel_ext = {{(W - 1){vel[F]}}, vel};

    always @(posedge clk or posedge rst) begin
        if (rst) begin
            pos_q   <= {(W + F){1'b0}};
            timer_q <= {T{1'b0}};
            hold_q  <= 1'b0;
            setup_q <= 1'b0;
            last_q  <= 1'b0;
            step_q  <= 1'b0;
            dir_q   <= 1'b0;
        end else if (tick) begin
            if (run & ~turn)
                pos_q <= pos_q + vel_ext;
            if (!idle)
                timer_q <= timer_q - 1'b1;
            else if (ld_step)
                timer_q <= steptime;
            else if (ld_dir)
                timer_q <= dirtime;
            // STEP ends when its time is up; a due step starts when the
            // previous one has ended (at least one tick low).
            if (act)
                step_q <= ~step_q & due;
            if (ld_step)
                last_q <= ~last_q;  // = the selected position bit
            // RUN -> HOLD when the direction must change and no step is due;
            // HOLD -> SETUP (DIR changes) or back to RUN when the velocity
            // turned back meanwhile; SETUP -> RUN when its time is up.
            hold_q  <= hold_q ? ~idle : act & turn & ~due;
            setup_q <= (setup_q & ~idle) | (hold_q & idle & turn);
            if (hold_q & idle & turn)
                dir_q <= vsign;
        end
    end

    assign pos = pos_q;
endmodule

`default_nettype wire
