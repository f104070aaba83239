// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_localbus: the PCI-style host bus target (spec/hostmot2.md section
// 17.1).  The host side is the simple synchronous 32-bit local bus that a
// PCI bridge (PLX 9030/9054, Mesa native) presents on its local side, in
// the ClockLow domain (the local bus clock is ClockLow):
//
//   lb_addr   byte address of the hm2 space (bits 1:0 ignored: aligned
//             32-bit accesses only; the 64 KiB PCI window maps 1:1)
//   lb_wr     one clock per 32-bit write of lb_wdata to lb_addr
//   lb_rd     one clock per 32-bit read of lb_addr
//   lb_rdata  read data, valid while lb_rvalid = 1 (two clocks after lb_rd)
//             and held until the next read completes
//
// One access per clock may be issued (reads and writes pipeline); a read
// and a write in the same clock both happen, the read returning the state
// before the write.  The strobes are registered once on the way in, so the
// host's timing does not reach into the module decoders.
`default_nettype none

module hm2_localbus (
    input  wire        clk,
    input  wire        rst,
    // host side
    input  wire [15:0] lb_addr,
    input  wire [31:0] lb_wdata,
    input  wire        lb_wr,
    input  wire        lb_rd,
    output wire [31:0] lb_rdata,
    output reg         lb_rvalid,
    // internal hm2 register bus (README.md)
    output reg  [15:0] bus_addr,
    output reg  [31:0] bus_wdata,
    output reg         bus_we,
    output reg         bus_re,
    input  wire [31:0] bus_rdata
);
    always @(posedge clk) begin
        if (rst) begin
            bus_addr  <= 16'd0;
            bus_wdata <= 32'd0;
            bus_we    <= 1'b0;
            bus_re    <= 1'b0;
            lb_rvalid <= 1'b0;
        end else begin
            bus_addr  <= lb_addr;
            bus_wdata <= lb_wdata;
            bus_we    <= lb_wr;
            bus_re    <= lb_rd;
            // The modules answer one clock after bus_re.
            lb_rvalid <= bus_re;
        end
    end

    assign lb_rdata = bus_rdata;
endmodule

`default_nettype wire
