// SPDX-License-Identifier: GPL-2.0-or-later
//
// Test wrapper: one hm2_sserial port of two channels at 8 clocks per bit,
// with channel 0's TxData/RxData as single-bit signals for the remote model
// (channel 1 has no remote: its RxData idles high).
`default_nettype none

module hm2_sserial_tb (
    input  wire        clk,
    input  wire        rst,
    input  wire [15:0] bus_addr,
    input  wire [31:0] bus_wdata,
    input  wire        bus_we,
    input  wire        bus_re,
    output wire [31:0] bus_rdata,
    output wire        tx0,
    input  wire        rx0,
    input  wire [1:0]  rx      // the test sets it once; bit 0 is replaced by rx0
);
    wire [1:0] tx;
    assign tx0 = tx[0];
    hm2_sserial #(.BASE(16'h5A00), .NUM(1), .NCHAN(2), .DIV(8)) u_ss (
        .clk(clk), .rst(rst), .bus_addr(bus_addr), .bus_wdata(bus_wdata), .bus_we(bus_we),
        .bus_re(bus_re), .bus_rdata(bus_rdata), .tx(tx), .rx({rx[1], rx0})
    );
    /* verilator lint_off UNUSEDSIGNAL */
    wire unused = rx[0] | tx[1];
    /* verilator lint_on UNUSEDSIGNAL */
endmodule

`default_nettype wire
