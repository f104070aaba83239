// SPDX-License-Identifier: GPL-2.0-or-later
//
// pluto_epp: the EPP peripheral front end of the Pluto-P firmwares.
//
// Register protocol (spec/pluto.md section 2):
//  - a 5-bit address register, loaded by an address-write cycle from data
//    bits 4..0 and incremented after every data cycle (read or write);
//  - writes are 16-bit: a byte at an even address is kept as the low byte,
//    a byte at an odd address commits {byte, low byte} to register addr[3:0]
//    (wr_stb for one clock, wr_addr / wr_data valid with it);
//  - reads are 32-bit: a read at addr[1:0] = 0 snapshots rd_data (the
//    register rd_sel = addr[4:2]) into a buffer and returns its byte 0; the
//    reads at addr[1:0] = 1, 2, 3 return buffer bytes 1, 2, 3.  A read that
//    does not start aligned returns bytes of the buffer as it was (no
//    snapshot, no side effect).  rd_stb is high in the clock that takes the
//    snapshot so the core can clear read-once flags.  rd_hit = 0 says that
//    rd_sel names no register: the buffer then keeps its old contents (the
//    original firmware returns the stale buffer for selectors 5-7).
//  - the low byte of a write is kept in its own register (SHARED_LO = 0)
//    or in byte 0 of the read buffer (SHARED_LO = 1: 8 flip-flops fewer,
//    a multiplexer more per bit).  The two are never needed at once (the
//    driver writes and reads in separate bursts); what changes is that a
//    write at an even address also sets byte 0 of what a later stale read
//    returns.  pluto_servo, short of flip-flops, shares; pluto_step, short
//    of LUTs, does not;
//  - an address-read cycle returns {3'b000, address}.
//
// Handshake: the two strobes are ORed and synchronized (two flip-flops);
// the access happens at the synchronized strobe edge (50-75 ns after the
// pin), the data bus is driven from the next clock and the acknowledge is
// given one clock after that (100-125 ns after the strobe).  Bus drive
// ends as soon as the synchronized strobe is gone, the acknowledge one
// clock later.  The handshake state is a 2-bit Gray counter (idle,
// accessed, driving, acknowledging): in a normal cycle one bit changes per
// clock, so the nWait and bus-enable decodes do not glitch.  Nothing here waits for the host: a strobe that is never
// released keeps the acknowledge up but blocks nothing else, and a strobe
// of any length, even one that ends before it is acknowledged, leaves the
// front end ready for the next cycle.
//
// ACK_LEVEL is the level of the nWait pin while acknowledging: 1 is the
// IEEE 1284 EPP handshake (what PC ports expect), 0 the inverted pin that
// spec/pluto.md section 12 reports for the original Pluto-P firmware.
//
// Only the strobes are synchronized.  EPP hosts set nWrite and the data
// before they assert a strobe and hold them until it ends, so the data
// bus, nWrite and nAddrStr are stable for >= 50 ns whenever the access
// clock samples them (2-3 clocks after the strobe pin fell), and the bus
// enable and the address-read byte may follow nWrite / nAddrStr directly.
// If both strobes are seen at once the cycle is an address cycle.
// nReset (the port's nInit line, one synchronizer stage) low clears the
// address register, the buffer and the handshake; it does not touch the
// core's registers.
`default_nettype none

module pluto_epp #(
    parameter [0:0] ACK_LEVEL = 1'b1,
    parameter [0:0] SHARED_LO = 1'b1
) (
    input  wire        clk,
    input  wire        rst,
    // EPP pins (the data bus split into in / out / output enable)
    input  wire [7:0]  epp_d_i,
    output wire [7:0]  epp_d_o,
    output wire        epp_d_oe,
    input  wire        epp_nwrite,
    input  wire        epp_ndatastr,
    input  wire        epp_naddrstr,
    input  wire        epp_nreset,
    output wire        epp_nwait,
    // register side
    output wire        wr_stb,
    output wire [3:0]  wr_addr,
    output wire [15:0] wr_data,
    output wire        rd_stb,
    output wire [2:0]  rd_sel,
    input  wire [31:0] rd_data,
    input  wire        rd_hit
);
    reg  [1:0] strobe_sq;  // synchronizer of (nDataStr low | nAddrStr low)
    reg        nreset_q;
    always @(posedge clk) begin
        strobe_sq <= {strobe_sq[0], ~(epp_ndatastr & epp_naddrstr)};
        nreset_q  <= epp_nreset;
    end
    wire strobe_s = strobe_sq[1];
    wire soft_rst = rst | ~nreset_q;

    // Handshake: 00 idle, 01 accessed, 11 driving, 10 acknowledging.
    reg  [1:0]  hs_q;
    reg  [4:0]  addr_q;
    reg  [31:0] buf_q;  // read buffer
    reg  [7:0]  lo_q;   // write low byte (SHARED_LO = 0)
    wire [7:0]  lo = SHARED_LO ? buf_q[7:0] : lo_q;

    wire start   = strobe_s & (hs_q == 2'b00);
    wire is_addr = ~epp_naddrstr;
    wire is_rd   = epp_nwrite;
    wire data_rd = start & ~is_addr & is_rd;
    wire data_wr = start & ~is_addr & ~is_rd;

    assign rd_sel  = addr_q[4:2];
    assign rd_stb  = data_rd & (addr_q[1:0] == 2'b00) & rd_hit;
    assign wr_stb  = data_wr & addr_q[0];
    assign wr_addr = addr_q[3:0];
    assign wr_data = {epp_d_i, lo};

    always @(posedge clk or posedge soft_rst) begin
        if (soft_rst) begin
            hs_q   <= 2'b00;
            addr_q <= 5'd0;
            buf_q  <= 32'd0;
            lo_q   <= 8'd0;
        end else begin
            if (!strobe_s)
                hs_q <= 2'b00;
            else
                case (hs_q)
                    2'b00:   hs_q <= 2'b01;
                    2'b01:   hs_q <= 2'b11;
                    default: hs_q <= 2'b10;
                endcase
            if (start) begin
                if (is_addr) begin
                    if (!is_rd)
                        addr_q <= epp_d_i[4:0];
                end else begin
                    addr_q <= addr_q + 5'd1;
                end
            end
            if (rd_stb)
                buf_q <= rd_data;
            else if (SHARED_LO && data_wr && !addr_q[0])
                buf_q[7:0] <= epp_d_i;
            if (!SHARED_LO && data_wr && !addr_q[0])
                lo_q <= epp_d_i;
        end
    end

    // The byte of the cycle in progress: the address was already stepped
    // past it, so buffer byte addr[1:0] - 1.
    reg [7:0] rbyte;
    always @(*) begin
        case (addr_q[1:0])
            2'd1:    rbyte = buf_q[7:0];
            2'd2:    rbyte = buf_q[15:8];
            2'd3:    rbyte = buf_q[23:16];
            default: rbyte = buf_q[31:24];
        endcase
    end

    assign epp_d_o   = is_addr ? {3'b000, addr_q} : rbyte;
    // The bus is let go one clock before the acknowledge ends (strobe_s
    // falls a clock before hs_q returns to idle), so a host that starts
    // its next cycle on "ready" never finds the bus still driven.
    assign epp_d_oe  = hs_q[1] & strobe_s & is_rd;
    assign epp_nwait = (hs_q == 2'b10) ? ACK_LEVEL : ~ACK_LEVEL;
endmodule

`default_nettype wire
