// SPDX-License-Identifier: GPL-2.0-or-later
//
// pluto_epp: the EPP peripheral front end of the Pluto-P firmwares.
//
// Register protocol (spec/pluto.md section 2):
//  - a 5-bit address register, loaded by an address-write cycle from data
//    bits 4..0 and incremented after every data cycle (read or write);
//  - writes are 16-bit: a byte at an even address is kept as the low byte,
//    a byte at an odd address commits {byte, low byte} to register addr[3:0]
//    (wr_stb_q for one clock);
//  - reads are 32-bit: a read at addr[1:0] = 0 snapshots rd_data (the
//    register rd_sel = addr[4:2]) into a buffer and returns its byte 0; the
//    reads at addr[1:0] = 1, 2, 3 return buffer bytes 1, 2, 3.  A read that
//    does not start aligned returns bytes of the buffer as it was (no
//    snapshot, no side effect).  rd_stb is high in the clock that takes the
//    snapshot so the core can clear read-once flags.  rd_hit = 0 says that
//    rd_sel names no register: the buffer then keeps its old contents (the
//    original firmware returns the stale buffer for selectors 5-7).
//  - an address-read cycle returns {3'b000, address}.
//
// Handshake: the strobes and nWrite are synchronized (two flip-flops); the
// access happens at the synchronized strobe edge (50-75 ns after the pin),
// read data is put on the bus one clock later and the acknowledge is given
// two clocks after the access (100-125 ns after the strobe).  Acknowledge
// and bus drive end as soon as the synchronized strobe is gone.  Nothing
// here waits for the host: a strobe that is never released keeps the
// acknowledge up but blocks nothing else, and a strobe of any length, even
// one that ends before it is acknowledged, leaves the front end ready for
// the next cycle.
//
// ACK_LEVEL is the level of the nWait pin while acknowledging: 1 is the
// IEEE 1284 EPP handshake (what PC ports expect), 0 the inverted pin that
// spec/pluto.md section 12 reports for the original Pluto-P firmware.
//
// The data bus is not passed through a synchronizer: it is captured only at
// the access clock, which comes 2-3 clocks after the strobe pin fell, and
// EPP hosts set nWrite and the data before they assert the strobe and hold
// them until it ends, so the bus is stable for >= 50 ns whenever a
// flip-flop samples it.  The strobes that qualify it are synchronized.
//
// If both strobes are seen at once the cycle is an address cycle.
// nReset (the port's nInit line) low clears the address register, the low
// byte latch and the handshake; it does not touch the core's registers.
`default_nettype none

module pluto_epp #(
    parameter [0:0] ACK_LEVEL = 1'b1
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
    output reg         wr_stb_q,
    output reg  [3:0]  wr_addr_q,
    output reg  [15:0] wr_data_q,
    output wire        rd_stb,
    output wire [2:0]  rd_sel,
    input  wire [31:0] rd_data,
    input  wire        rd_hit
);
    // {nReset, nWrite, nAddrStr, nDataStr}, idle high.
    wire [3:0] pins_s;
    sync_ff #(.WIDTH(4), .STAGES(2), .RESET_VALUE(4'b1111)) u_sync (
        .clk(clk), .rst(rst),
        .d({epp_nreset, epp_nwrite, epp_naddrstr, epp_ndatastr}),
        .q(pins_s)
    );
    wire ds_s     = ~pins_s[0];
    wire as_s     = ~pins_s[1];
    wire write_s  = ~pins_s[2];
    wire soft_rst = rst | ~pins_s[3];
    wire strobe_s = ds_s | as_s;

    reg        strobe_q;     // strobe_s one clock ago, for the edge
    reg  [1:0] ackdly_q;     // the access travelling towards the acknowledge
    reg        ack_q;        // the WAIT flag
    reg        drive_q;      // data bus driven (read cycles)
    reg        rdcyc_q;      // the current cycle is a read
    reg  [4:0] addr_q;
    reg  [7:0] lo_q;         // low byte of a 16-bit write
    reg  [31:0] buf_q;       // 32-bit read buffer
    reg  [7:0] dout_q;       // byte put on the bus

    wire start   = strobe_s & ~strobe_q;
    wire is_addr = as_s;
    wire is_rd   = ~write_s;

    assign rd_sel = addr_q[4:2];
    assign rd_stb = start & ~is_addr & is_rd & (addr_q[1:0] == 2'b00) & rd_hit;

    reg [7:0] rbyte;
    always @(*) begin
        case (addr_q[1:0])
            2'd0: rbyte = rd_hit ? rd_data[7:0] : buf_q[7:0];
            2'd1: rbyte = buf_q[15:8];
            2'd2: rbyte = buf_q[23:16];
            default: rbyte = buf_q[31:24];
        endcase
    end

    always @(posedge clk) begin
        if (soft_rst) begin
            strobe_q  <= 1'b0;
            ackdly_q  <= 2'b00;
            ack_q     <= 1'b0;
            drive_q   <= 1'b0;
            rdcyc_q   <= 1'b0;
            addr_q    <= 5'd0;
            lo_q      <= 8'd0;
            buf_q     <= 32'd0;
            dout_q    <= 8'd0;
            wr_stb_q  <= 1'b0;
            wr_addr_q <= 4'd0;
            wr_data_q <= 16'd0;
        end else begin
            strobe_q <= strobe_s;
            wr_stb_q <= 1'b0;
            ackdly_q <= strobe_s ? {ackdly_q[0], start} : 2'b00;
            ack_q    <= strobe_s & (ack_q | ackdly_q[1]);
            drive_q  <= strobe_s & rdcyc_q & (drive_q | ackdly_q[0]);
            if (start) begin
                rdcyc_q <= is_rd;
                if (is_addr) begin
                    if (is_rd)
                        dout_q <= {3'b000, addr_q};
                    else
                        addr_q <= epp_d_i[4:0];
                end else begin
                    addr_q <= addr_q + 5'd1;
                    if (is_rd) begin
                        dout_q <= rbyte;
                        if (addr_q[1:0] == 2'b00 && rd_hit)
                            buf_q <= rd_data;
                    end else if (!addr_q[0]) begin
                        lo_q <= epp_d_i;
                    end else begin
                        wr_stb_q  <= 1'b1;
                        wr_addr_q <= addr_q[3:0];
                        wr_data_q <= {epp_d_i, lo_q};
                    end
                end
            end
        end
    end

    assign epp_d_o   = dout_q;
    assign epp_d_oe  = drive_q;
    assign epp_nwait = ack_q ? ACK_LEVEL : ~ACK_LEVEL;
endmodule

`default_nettype wire
