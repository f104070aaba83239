// SPDX-License-Identifier: GPL-2.0-or-later
//
// pluto_wdt: the Pluto-P watchdog.  Off after power-up.  pet sets it enabled
// and clears the counter; tick increments the counter, which saturates at
// 2^WIDTH-1.  trip = enabled and saturated (127 ticks, about 6.5 ms with
// the firmwares' ~51 us tick).  Only a reset disables it again; a pet in
// the same clock as a tick wins.
`default_nettype none

module pluto_wdt #(
    parameter integer WIDTH = 7
) (
    input  wire clk,
    input  wire rst,
    input  wire tick,
    input  wire pet,
    output wire trip
);
    reg [WIDTH-1:0] cnt_q;
    reg             en_q;
    wire            full = &cnt_q;

    always @(posedge clk or posedge rst) begin
        if (rst) begin
            cnt_q <= {WIDTH{1'b0}};
            en_q  <= 1'b0;
        end else if (pet) begin
            cnt_q <= {WIDTH{1'b0}};
            en_q  <= 1'b1;
        end else if (tick && !full) begin
            cnt_q <= cnt_q + 1'b1;
        end
    end

    assign trip = en_q & full;
endmodule

`default_nettype wire
