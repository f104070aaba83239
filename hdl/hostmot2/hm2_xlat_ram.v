// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_xlat_ram: the EPP front end's address translation RAM as Mesa's 7i43
// firmwares list it (GTag 11 "AddrX", MD base 0x7800, 4 registers, one
// instance; spec/hostmot2.md section 9.7).
//
//   BASE .. BASE+0x3FC   256 x 32-bit words, read/write
//
// Word k holds a translated address for burst slot k.  The LinuxCNC driver
// never uses it (it skips GTag 11); the RAM is here so the IDROM, the
// address map and the read-back match Mesa's firmware.  The translated
// window itself (0x7C00) is not decoded (reads there return 0).
`default_nettype none

module hm2_xlat_ram #(
    parameter [15:0] BASE = 16'h7800  // MD BaseAddress (1 KiB aligned)
) (
    input  wire        clk,
    input  wire        rst,
    // bits 1:0 are ignored (aligned 32-bit accesses only)
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [15:0] bus_addr,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire [31:0] bus_wdata,
    input  wire        bus_we,
    input  wire        bus_re,
    output reg  [31:0] bus_rdata
);
    reg [31:0] mem [0:255];
    wire       sel  = (bus_addr[15:10] == BASE[15:10]);
    wire [7:0] word = bus_addr[9:2];

    // Configuration clears the RAM (block RAM initial contents).
    integer n;
    initial begin
        for (n = 0; n < 256; n = n + 1)
            mem[n] = 32'd0;
    end

    // Synchronous read and write: maps onto block RAM.
    reg [31:0] q;
    always @(posedge clk) begin
        if (bus_we && sel)
            mem[word] <= bus_wdata;
        q <= mem[word];
    end

    reg sel_q;
    always @(posedge clk) begin
        if (rst)
            sel_q <= 1'b0;
        else if (bus_re)
            sel_q <= sel;
    end

    // Read data the clock after bus_re, held until the next read, 0 when
    // that read was not addressed here (bus convention, README.md).
    reg        hold_q;
    reg [31:0] held_q;
    always @(posedge clk) begin
        if (rst) begin
            hold_q <= 1'b0;
            held_q <= 32'd0;
        end else begin
            hold_q <= bus_re;
            if (hold_q)
                held_q <= sel_q ? q : 32'd0;
        end
    end
    always @(*) bus_rdata = hold_q ? (sel_q ? q : 32'd0) : held_q;
endmodule

`default_nettype wire
