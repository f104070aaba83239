// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_led: the LED register (spec/hostmot2.md section 9.3, GTag 128,
// 1 register, write-only, reads return 0).
//
// LED i shows bit 32-NUM_LEDS+i of the last word written (bit 31 is the
// highest LED, the driver's CR01).  leds[i] = 1 means the LED is lit; the
// board's LED pins are active low, which is the board's business.
`default_nettype none

module hm2_led #(
    parameter [15:0]  BASE     = 16'h0200,  // MD BaseAddress
    parameter integer NUM_LEDS = 8          // 1..32
) (
    input  wire                clk,
    input  wire                rst,
    // Byte address; bits 1:0 are ignored (aligned 32-bit accesses only).
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [15:0]         bus_addr,
    // Only the top NUM_LEDS bits carry LEDs.
    input  wire [31:0]         bus_wdata,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire                bus_we,
    output wire [NUM_LEDS-1:0] leds
);
    reg [NUM_LEDS-1:0] led_q;
    wire sel = (bus_addr[15:8] == BASE[15:8]) && (bus_addr[7:2] == 6'd0);

    always @(posedge clk) begin
        if (rst)
            led_q <= {NUM_LEDS{1'b0}};
        else if (bus_we && sel)
            led_q <= bus_wdata[31 -: NUM_LEDS];
    end

    assign leds = led_q;
endmodule

`default_nettype wire
