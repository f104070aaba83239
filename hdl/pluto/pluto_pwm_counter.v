// SPDX-License-Identifier: GPL-2.0-or-later
//
// pluto_pwm_counter: the PWM period counter shared by the four pluto_servo
// PWM channels.  Counts 0 .. PERIOD-1 and restarts (PERIOD = 2047 clocks,
// 51.175 us, 19.54 kHz at 40 MHz); wrap is high in the clock the counter
// holds PERIOD-1 (the watchdog's tick).
`default_nettype none

module pluto_pwm_counter #(
    parameter integer WIDTH  = 11,
    parameter integer PERIOD = 2047
) (
    input  wire             clk,
    input  wire             rst,
    output wire [WIDTH-1:0] cnt,
    output wire             wrap
);
    localparam integer     LAST_I = PERIOD - 1;
    localparam [WIDTH-1:0] LAST   = LAST_I[WIDTH-1:0];
    reg [WIDTH-1:0] cnt_q;

    assign wrap = (cnt_q == LAST);

    always @(posedge clk or posedge rst) begin
        if (rst)
            cnt_q <= {WIDTH{1'b0}};
        else if (wrap)
            cnt_q <= {WIDTH{1'b0}};
        else
            cnt_q <= cnt_q + 1'b1;
    end

    assign cnt = cnt_q;
endmodule

`default_nettype wire
