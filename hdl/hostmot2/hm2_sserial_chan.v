// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_sserial_chan: one Smart Serial channel: its UART and the frame engine
// that runs one host command on it (spec/hostmot2.md section 9.9).
//
// Frames on the wire (each ends with a CRC-8, polynomial 0x07, initial
// value 0, over every byte before it):
//   discover   host: 01 mode                 remote: name[4] unit[4]
//                                                    ptoc[2] gtoc[2] in_bits out_bits
//   read       host: 02 addr_lo addr_hi n    remote: data[n]          (n = 1..4)
//   write      host: 03 addr_lo addr_hi n data[n]   remote: status
//   process    host: 04 out[ceil(out_bits/8)] remote: status in[ceil(in_bits/8)]
// The remote answers within TIMEOUT bit times after the host's last byte,
// and bytes of one frame follow each other within GAP bit times.
//
// op: 1 start (discover with mode), 2 remote command (CS: bits 31..28 = 1
// read / 2 write, 25..24 = n-1, 15..0 address; write data from out0),
// 3 process data.  done pulses one clock when the op has finished; err
// holds the error flags of the last op (bit 0 no answer, 1 CRC, 2 framing,
// 3 wrong length, 4 bad command).
`default_nettype none

module hm2_sserial_chan #(
    parameter integer DIV = 13  // ClockLow periods per bit
) (
    input  wire        clk,
    input  wire        rst,
    input  wire [1:0]  op,
    input  wire        go,
    input  wire [31:0] cs,       // host CS register (mode / remote command)
    input  wire [95:0] out_data, // host interface registers 2..0 (process data out)
    output reg         busy,
    output reg         done,
    output reg  [4:0]  err,
    output reg  [7:0]  status,   // remote status byte of the last write/process
    output reg  [7:0]  in_bits,  // from discovery
    output reg  [7:0]  out_bits,
    output reg  [95:0] in_data,  // host interface registers 2..0 (read side)
    output wire        tx,
    input  wire        rx
);
    localparam integer TIMEOUT = 64;   // bit times until the answer starts
    localparam integer GAP     = 24;   // bit times between bytes of an answer
    localparam [1:0] OP_START = 2'd1, OP_CMD = 2'd2, OP_PROC = 2'd3;
    localparam [2:0] S_IDLE = 3'd0, S_TX = 3'd1, S_TXWAIT = 3'd2, S_RX = 3'd3, S_END = 3'd4;

    function [7:0] crc8(input [7:0] c, input [7:0] d);
        integer k;
        reg [7:0] r;
        begin
            r = c ^ d;
            for (k = 0; k < 8; k = k + 1)
                r = r[7] ? {r[6:0], 1'b0} ^ 8'h07 : {r[6:0], 1'b0};
            crc8 = r;
        end
    endfunction

    reg  [2:0]   st_q;
    reg  [1:0]   op_q;
    // bits 27 and 23..16 of a remote command are not used
    /* verilator lint_off UNUSEDSIGNAL */
    reg  [31:0]  cs_q;
    /* verilator lint_on UNUSEDSIGNAL */
    reg  [4:0]   txi_q, txn_q;    // byte index, frame length without CRC
    reg  [4:0]   rxi_q, rxn_q;    // answer length without CRC
    reg  [7:0]   crc_q;
    // answer bytes, byte k at [8k +: 8] (at most 14 bytes are kept)
    /* verilator lint_off UNUSEDSIGNAL */
    reg  [127:0] rxbuf_q;
    /* verilator lint_on UNUSEDSIGNAL */
    reg  [15:0]  wait_q;          // clocks left for the next answer byte
    reg          tx_go;
    reg  [7:0]   tx_byte;         // byte txi_q of the host frame
    reg  [7:0]   txb_q;           // the byte handed to the UART
    wire         tx_busy, rx_valid, rx_ferr, rx_busy;
    wire [7:0]   rx_byte;

    hm2_sserial_uart #(.DIV(DIV)) u_uart (
        .clk(clk), .rst(rst), .tx_go(tx_go), .tx_byte(txb_q), .tx_busy(tx_busy), .tx_q(tx),
        .rx_pin(rx), .rx_enable(st_q == S_RX), .rx_valid(rx_valid), .rx_byte(rx_byte),
        .rx_ferr(rx_ferr), .rx_busy(rx_busy)
    );

    wire [4:0] nbytes  = {3'd0, cs_q[25:24]} + 5'd1;
    // ceil(bits/8) for bits <= 96, computed without a divider
    function [4:0] bytes_of(input [7:0] b);
        bytes_of = b[7:3] + {4'd0, b[2:0] != 3'd0};
    endfunction

    // byte txi of the host frame
    always @(*) begin
        tx_byte = 8'd0;
        case (op_q)
            OP_START: tx_byte = (txi_q == 5'd0) ? 8'h01 : {4'd0, cs_q[3:0]};
            OP_CMD: begin
                case (txi_q)
                    5'd0: tx_byte = (cs_q[31:28] == 4'd2) ? 8'h03 : 8'h02;
                    5'd1: tx_byte = cs_q[7:0];
                    5'd2: tx_byte = cs_q[15:8];
                    5'd3: tx_byte = {5'd0, cs_q[26:24]} + 8'd1;
                    default: tx_byte = out_data[(txi_q - 5'd4) * 8 +: 8];
                endcase
            end
            default: tx_byte = (txi_q == 5'd0) ? 8'h04 : out_data[(txi_q - 5'd1) * 8 +: 8];
        endcase
        if (txi_q == txn_q)
            tx_byte = crc_q;
    end

    always @(posedge clk) begin
        if (rst) begin
            st_q     <= S_IDLE;
            op_q     <= 2'd0;
            cs_q     <= 32'd0;
            txi_q    <= 5'd0;
            txn_q    <= 5'd0;
            rxi_q    <= 5'd0;
            rxn_q    <= 5'd0;
            crc_q    <= 8'd0;
            rxbuf_q  <= 128'd0;
            wait_q   <= 16'd0;
            tx_go    <= 1'b0;
            txb_q    <= 8'd0;
            busy     <= 1'b0;
            done     <= 1'b0;
            err      <= 5'd0;
            status   <= 8'd0;
            in_bits  <= 8'd0;
            out_bits <= 8'd0;
            in_data  <= 96'd0;
        end else begin
            done  <= 1'b0;
            tx_go <= 1'b0;
            case (st_q)
                S_IDLE: if (go) begin
                    op_q  <= op;
                    cs_q  <= cs;
                    busy  <= 1'b1;
                    err   <= 5'd0;
                    txi_q <= 5'd0;
                    crc_q <= 8'd0;
                    rxi_q <= 5'd0;
                    rxbuf_q <= 128'd0;  // bytes past the answer read 0
                    if (op == OP_START) begin
                        txn_q <= 5'd2;
                        rxn_q <= 5'd14;
                        st_q  <= S_TX;
                    end else if (op == OP_CMD) begin
                        if (cs[31:28] == 4'd1) begin
                            txn_q <= 5'd4;
                            rxn_q <= {3'd0, cs[25:24]} + 5'd1;
                            st_q  <= S_TX;
                        end else if (cs[31:28] == 4'd2) begin
                            txn_q <= 5'd5 + {3'd0, cs[25:24]};
                            rxn_q <= 5'd1;
                            st_q  <= S_TX;
                        end else begin
                            err  <= 5'b10000;
                            st_q <= S_END;
                        end
                    end else if (op == OP_PROC) begin
                        txn_q <= 5'd1 + bytes_of(out_bits);
                        rxn_q <= 5'd1 + bytes_of(in_bits);
                        st_q  <= S_TX;
                    end else begin
                        err  <= 5'b10000;
                        st_q <= S_END;
                    end
                end
                S_TX: if (!tx_busy && !tx_go) begin
                    tx_go <= 1'b1;
                    txb_q <= tx_byte;
                    crc_q <= crc8(crc_q, tx_byte);
                    if (txi_q == txn_q) begin
                        st_q <= S_TXWAIT;
                    end
                    txi_q <= txi_q + 5'd1;
                end
                S_TXWAIT: if (!tx_busy && !tx_go) begin
                    st_q   <= S_RX;
                    crc_q  <= 8'd0;
                    wait_q <= TIMEOUT[15:0] * DIV[15:0];
                end
                S_RX: begin
                    if (rx_valid) begin
                        wait_q <= GAP[15:0] * DIV[15:0];
                        if (rx_ferr) begin
                            err[2] <= 1'b1;
                            st_q   <= S_END;
                        end else if (rxi_q == rxn_q) begin
                            if (crc_q != rx_byte)
                                err[1] <= 1'b1;
                            st_q <= S_END;
                        end else begin
                            rxbuf_q[rxi_q * 8 +: 8] <= rx_byte;
                            crc_q <= crc8(crc_q, rx_byte);
                            rxi_q <= rxi_q + 5'd1;
                        end
                    end else if (!rx_busy) begin
                        if (wait_q == 16'd0) begin
                            // no answer at all, or an answer cut short
                            err[0] <= (rxi_q == 5'd0);
                            err[3] <= (rxi_q != 5'd0);
                            st_q   <= S_END;
                        end else begin
                            wait_q <= wait_q - 16'd1;
                        end
                    end
                end
                default: begin  // S_END: publish the answer
                    busy <= 1'b0;
                    done <= 1'b1;
                    st_q <= S_IDLE;
                    if (err == 5'd0) begin
                        case (op_q)
                            OP_START: begin
                                in_data  <= rxbuf_q[95:0];
                                in_bits  <= rxbuf_q[103:96];
                                out_bits <= rxbuf_q[111:104];
                            end
                            OP_CMD: begin
                                if (cs_q[31:28] == 4'd1)
                                    in_data[31:0] <= rxbuf_q[31:0] &
                                        (32'hFFFFFFFF >> (8 * (4 - nbytes)));
                                else
                                    status <= rxbuf_q[7:0];
                            end
                            default: begin
                                status  <= rxbuf_q[7:0];
                                in_data <= rxbuf_q[103:8];
                            end
                        endcase
                    end
                end
            endcase
        end
    end
endmodule

`default_nettype wire
