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
    localparam [1:0] RUN = 2'd0, HOLD = 2'd1, SETUP = 2'd2;

    reg [W+F-1:0] pos_q;
    reg [T-1:0]   timer_q;
    reg [T-1:0]   dtimer_q;
    reg [1:0]     phase_q;
    reg           last_q;

    wire           vsign   = vel[F];
    wire [3:0]     taps    = pos_q[F+3:F];
    wire           sel     = taps[tap];
    wire           due     = sel ^ last_q;
    wire           turn    = vsign ^ dir_q;
    wire           run     = (phase_q == RUN) | ((phase_q == SETUP) & (dtimer_q == {T{1'b0}}));
    wire [W+F-1:0] vel_ext = {{(W - 1){vel[F]}}, vel};

    always @(posedge clk) begin
        if (rst) begin
            pos_q    <= {(W + F){1'b0}};
            timer_q  <= {T{1'b0}};
            dtimer_q <= {T{1'b0}};
            phase_q  <= RUN;
            last_q   <= 1'b0;
            step_q   <= 1'b0;
            dir_q    <= 1'b0;
        end else if (tick) begin
            if (run) begin
                phase_q <= RUN;
                if (timer_q != {T{1'b0}}) begin
                    timer_q <= timer_q - 1'b1;
                end else if (step_q) begin
                    step_q <= 1'b0;
                    if (turn && !due) begin
                        phase_q  <= HOLD;
                        dtimer_q <= dirtime;
                    end
                end else if (due) begin
                    step_q  <= 1'b1;
                    timer_q <= steptime;
                    last_q  <= sel;
                end else if (turn) begin
                    phase_q  <= HOLD;
                    dtimer_q <= dirtime;
                end
                if (!turn)
                    pos_q <= pos_q + vel_ext;
            end else if (dtimer_q != {T{1'b0}}) begin
                dtimer_q <= dtimer_q - 1'b1;
            end else if (phase_q == HOLD) begin
                if (turn) begin
                    dir_q    <= vsign;
                    phase_q  <= SETUP;
                    dtimer_q <= dirtime;
                end else begin
                    phase_q <= RUN;
                end
            end else begin
                // phase 3 is never entered; recover to RUN if it ever is.
                phase_q <= RUN;
            end
        end
    end

    assign pos = pos_q;
endmodule

`default_nettype wire
