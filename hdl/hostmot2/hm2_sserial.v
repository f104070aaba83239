// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_sserial: Smart Serial ports (GTag 193, version 0, 6 registers,
// Strides 0x10: register stride 0x100, port stride 0x40, MPBitmap 0x3C;
// spec/hostmot2.md section 9.9).  NUM ports of NCHAN channels each.
//
//   BASE+0x000+0x40p        Command  W: command, R: the command while it
//                                     runs, 0 when it has finished
//   BASE+0x100+0x40p        Data     R: result of the last command
//                                     (start/doit: mask of failed channels;
//                                     local read: the byte); W: stored
//   BASE+0x200+0x40p+4c     CS       W: channel mode (before a start) or the
//                                     remote command (setup mode);
//                                     R: {out_bits, in_bits, state, err, status}
//   BASE+0x300/0x400/0x500  Interface 0/1/2: W: process data out bits
//         +0x40p+4c                  31..0/63..32/95..64; R: data in (the
//                                     remote's answer)
//
// Commands: 0x800|mask stop (mask 0 = every channel); 0x900|mask start in
// setup mode, 0xA00|mask start in normal mode (discovery: Interface 0 =
// remote name, 1 = unit number, 2 = PTOC | GTOC<<16, CS = sizes); 0x1000|mask
// doit (normal mode: process data, setup mode: the CS remote command);
// 0x2000|addr read a local byte (0 channels, 1 version, 2/3 bit divisor)
// into Data; 0x3000|addr write local (accepted, no effect).
//
// CS read: bits 31..24 out_bits, 23..16 in_bits, 15..14 state (0 stopped,
// 1 setup, 2 normal), 12..8 error flags of the last transfer (8 no answer,
// 9 CRC, 10 framing, 11 wrong length, 12 bad command or channel stopped),
// 7..0 the remote's status byte.
`default_nettype none

module hm2_sserial #(
    parameter [15:0]  BASE  = 16'h5A00,  // MD BaseAddress
    parameter integer NUM   = 1,         // ports (MD Instances, 1..4)
    parameter integer NCHAN = 4,         // channels per port (1..8)
    parameter integer DIV   = 13         // ClockLow periods per bit
) (
    input  wire                  clk,
    input  wire                  rst,
    input  wire [15:0]           bus_addr,  // bits 1:0 ignored
    input  wire [31:0]           bus_wdata,
    input  wire                  bus_we,
    input  wire                  bus_re,
    output reg  [31:0]           bus_rdata,
    output wire [NUM*NCHAN-1:0]  tx,        // channel p*NCHAN+c
    input  wire [NUM*NCHAN-1:0]  rx
);
    localparam integer NREGS = 6;
    localparam integer NC = NUM * NCHAN;
    localparam [7:0] VERSION = 8'd1;
    localparam [15:0] DIV_W = DIV[15:0];

    wire [7:0] page     = bus_addr[15:8];
    wire [7:0] reg_off  = page - BASE[15:8];
    wire       in_range = (page >= BASE[15:8]) && (reg_off < NREGS[7:0]);
    wire [1:0] port     = bus_addr[7:6];
    wire [3:0] chan     = bus_addr[5:2];
    wire       port_ok  = ({30'd0, port} < NUM);
    wire       chan_ok  = ({28'd0, chan} < NCHAN);
    /* verilator lint_off UNUSEDSIGNAL */
    wire [1:0] unused_a = bus_addr[1:0];
    /* verilator lint_on UNUSEDSIGNAL */

    // ---- per-channel host registers and engines
    reg  [NC*32-1:0] cs_q;
    reg  [NC*96-1:0] out_q;
    reg  [NC*2-1:0]  state_q;   // 0 stopped, 1 setup, 2 normal
    reg  [NC*2-1:0]  ch_op;
    reg  [NC-1:0]    ch_go;
    // busy is for tests and waveforms; the port tracks done pulses
    /* verilator lint_off UNUSEDSIGNAL */
    wire [NC-1:0]    ch_busy;
    /* verilator lint_on UNUSEDSIGNAL */
    wire [NC-1:0]    ch_done;
    wire [NC*5-1:0]  ch_err;
    wire [NC*8-1:0]  ch_status, ch_in_bits, ch_out_bits;
    wire [NC*96-1:0] ch_in;

    genvar g;
    generate
        for (g = 0; g < NC; g = g + 1) begin : g_chan
            hm2_sserial_chan #(.DIV(DIV)) u_chan (
                .clk(clk), .rst(rst), .op(ch_op[g*2 +: 2]), .go(ch_go[g]),
                .cs(cs_q[g*32 +: 32]), .out_data(out_q[g*96 +: 96]),
                .busy(ch_busy[g]), .done(ch_done[g]), .err(ch_err[g*5 +: 5]),
                .status(ch_status[g*8 +: 8]), .in_bits(ch_in_bits[g*8 +: 8]),
                .out_bits(ch_out_bits[g*8 +: 8]), .in_data(ch_in[g*96 +: 96]),
                .tx(tx[g]), .rx(rx[g])
            );
        end
    endgenerate

    // ---- per-port command state
    reg [NUM*16-1:0]    cmd_q;      // the running command, 0 = idle
    reg [NUM*32-1:0]    data_q;
    reg [NUM*NCHAN-1:0] pend_q;     // channels still working on the command
    reg [NUM*NCHAN-1:0] fail_q;

    integer p, c;
    wire [5:0] wk = {4'd0, port} * NCHAN[5:0] + {2'd0, chan};  // addressed channel
    always @(posedge clk) begin
        if (rst) begin
            cs_q    <= {NC*32{1'b0}};
            out_q   <= {NC*96{1'b0}};
            state_q <= {NC*2{1'b0}};
            ch_op   <= {NC*2{1'b0}};
            ch_go   <= {NC{1'b0}};
            cmd_q   <= {NUM*16{1'b0}};
            data_q  <= {NUM*32{1'b0}};
            pend_q  <= {NC{1'b0}};
            fail_q  <= {NC{1'b0}};
        end else begin
            ch_go <= {NC{1'b0}};
            for (p = 0; p < NUM; p = p + 1) begin
                // a command runs until every channel it started is done
                for (c = 0; c < NCHAN; c = c + 1) begin
                    if (ch_done[p*NCHAN+c] && pend_q[p*NCHAN+c]) begin
                        pend_q[p*NCHAN+c] <= 1'b0;
                        if (ch_err[(p*NCHAN+c)*5 +: 5] != 5'd0)
                            fail_q[p*NCHAN+c] <= 1'b1;
                        if (cmd_q[p*16 +: 16] >= 16'h0900 && cmd_q[p*16 +: 16] < 16'h0B00)
                            state_q[(p*NCHAN+c)*2 +: 2] <= (ch_err[(p*NCHAN+c)*5 +: 5] != 5'd0) ? 2'd0 :
                                                 (cmd_q[p*16 + 8] ? 2'd1 : 2'd2);
                    end
                end
                if (cmd_q[p*16 +: 16] != 16'd0 && pend_q[p*NCHAN +: NCHAN] == {NCHAN{1'b0}} &&
                    ch_go[p*NCHAN +: NCHAN] == {NCHAN{1'b0}}) begin
                    cmd_q[p*16 +: 16] <= 16'd0;
                    if (cmd_q[p*16 + 15 -: 4] != 4'h2)
                        data_q[p*32 +: 32] <= {{(32-NCHAN){1'b0}}, fail_q[p*NCHAN +: NCHAN]};
                end
            end

            if (bus_we && in_range && port_ok) begin
                case (reg_off)
                    8'd0: if (chan == 4'd0 && cmd_q[port*16 +: 16] == 16'd0)
                        start_command({30'd0, port}, bus_wdata[15:0]);
                    8'd1: if (chan == 4'd0) data_q[port*32 +: 32] <= bus_wdata;
                    8'd2: if (chan_ok) cs_q[wk*32 +: 32] <= bus_wdata;
                    8'd3: if (chan_ok) out_q[wk*96 +: 32] <= bus_wdata;
                    8'd4: if (chan_ok) out_q[wk*96 + 32 +: 32] <= bus_wdata;
                    8'd5: if (chan_ok) out_q[wk*96 + 64 +: 32] <= bus_wdata;
                    default: ;
                endcase
            end
        end
    end

    // Start command w on port pp (called from the clocked block above).
    task start_command(input integer pp, input [15:0] w);
        integer cc, kk;
        reg [7:0] mask;
        begin
            mask = w[7:0];
            fail_q[pp*NCHAN +: NCHAN] <= {NCHAN{1'b0}};
            if (w[15:12] == 4'h0 && w[11:8] == 4'h8) begin
                for (cc = 0; cc < NCHAN; cc = cc + 1)
                    if (mask == 8'd0 || mask[cc])
                        state_q[(pp*NCHAN+cc)*2 +: 2] <= 2'd0;
                data_q[pp*32 +: 32] <= 32'd0;
            end else if (w[15:12] == 4'h0 && (w[11:8] == 4'h9 || w[11:8] == 4'hA)) begin
                cmd_q[pp*16 +: 16] <= w;
                for (cc = 0; cc < NCHAN; cc = cc + 1) begin
                    kk = pp * NCHAN + cc;
                    if (mask[cc]) begin
                        ch_op[kk*2 +: 2] <= 2'd1;
                        ch_go[kk] <= 1'b1;
                        pend_q[kk] <= 1'b1;
                    end
                end
            end else if (w[15:12] == 4'h1) begin
                cmd_q[pp*16 +: 16] <= w;
                for (cc = 0; cc < NCHAN; cc = cc + 1) begin
                    kk = pp * NCHAN + cc;
                    if (mask[cc]) begin
                        if (state_q[kk*2 +: 2] == 2'd0) begin
                            fail_q[kk] <= 1'b1;
                        end else begin
                            ch_op[kk*2 +: 2] <= (state_q[kk*2 +: 2] == 2'd1) ? 2'd2 : 2'd3;
                            ch_go[kk] <= 1'b1;
                            pend_q[kk] <= 1'b1;
                        end
                    end
                end
            end else if (w[15:12] == 4'h2) begin
                case (w[7:0])
                    8'd0: data_q[pp*32 +: 32] <= NCHAN;
                    8'd1: data_q[pp*32 +: 32] <= {24'd0, VERSION};
                    8'd2: data_q[pp*32 +: 32] <= {24'd0, DIV_W[7:0]};
                    8'd3: data_q[pp*32 +: 32] <= {24'd0, DIV_W[15:8]};
                    default: data_q[pp*32 +: 32] <= 32'd0;
                endcase
            end
            // 0x3000|addr (write local) and unknown commands: accepted, no effect
        end
    endtask

    // ---- read back
    reg [31:0] rd_d;
    integer kr;
    always @(*) begin
        rd_d = 32'd0;
        kr = {30'd0, port} * NCHAN + {28'd0, chan};
        if (in_range && port_ok) begin
            case (reg_off)
                8'd0: if (chan == 4'd0) rd_d = {16'd0, cmd_q[port*16 +: 16]};
                8'd1: if (chan == 4'd0) rd_d = data_q[port*32 +: 32];
                8'd2: if (chan_ok) rd_d = {ch_out_bits[kr*8 +: 8], ch_in_bits[kr*8 +: 8],
                                           state_q[kr*2 +: 2], 1'b0, ch_err[kr*5 +: 5],
                                           ch_status[kr*8 +: 8]};
                8'd3: if (chan_ok) rd_d = ch_in[kr*96 +: 32];
                8'd4: if (chan_ok) rd_d = ch_in[kr*96 + 32 +: 32];
                8'd5: if (chan_ok) rd_d = ch_in[kr*96 + 64 +: 32];
                default: rd_d = 32'd0;
            endcase
        end
    end

    always @(posedge clk) begin
        if (rst)
            bus_rdata <= 32'd0;
        else if (bus_re)
            bus_rdata <= rd_d;
    end
endmodule

`default_nettype wire
