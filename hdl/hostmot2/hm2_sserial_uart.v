// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_sserial_uart: the byte UART of one Smart Serial channel (8 data bits
// LSB first, one start bit 0, one stop bit 1, idle 1), DIV ClockLow periods
// per bit.  Transmit: tx_go with tx_byte starts a byte when tx_busy is 0.
// Receive: a falling edge of the synchronized line starts a byte, each bit
// is sampled in its middle; rx_valid pulses for one clock with rx_byte and
// rx_ferr (stop bit was 0).  rx_enable = 0 ignores the line.
`default_nettype none

module hm2_sserial_uart #(
    parameter integer DIV = 13  // ClockLow periods per bit (>= 4)
) (
    input  wire       clk,
    input  wire       rst,
    input  wire       tx_go,
    input  wire [7:0] tx_byte,
    output wire       tx_busy,
    output reg        tx_q,       // the line (1 = idle)
    input  wire       rx_pin,     // raw pin level
    input  wire       rx_enable,
    output reg        rx_valid,
    output reg  [7:0] rx_byte,
    output reg        rx_ferr,
    output wire       rx_busy
);
    localparam integer CW = 8;
    localparam [CW-1:0] BIT_T  = DIV[CW-1:0] - 1'b1;
    localparam [CW-1:0] HALF_T = DIV[CW-1:0] / 2 - 1'b1;

    // ---- transmit: {stop, data, start} shifted out LSB first
    // bit 0 (the start bit) leaves through tx_q directly
    /* verilator lint_off UNUSEDSIGNAL */
    reg [9:0]    tx_sh_q;
    /* verilator lint_on UNUSEDSIGNAL */
    reg [3:0]    tx_n_q;     // bits left
    reg [CW-1:0] tx_t_q;
    assign tx_busy = (tx_n_q != 4'd0);

    always @(posedge clk) begin
        if (rst) begin
            tx_sh_q <= 10'h3FF;
            tx_n_q  <= 4'd0;
            tx_t_q  <= {CW{1'b0}};
            tx_q    <= 1'b1;
        end else if (!tx_busy) begin
            tx_q <= 1'b1;
            if (tx_go) begin
                tx_sh_q <= {1'b1, tx_byte, 1'b0};
                tx_n_q  <= 4'd10;
                tx_t_q  <= BIT_T;
                tx_q    <= 1'b0;
            end
        end else if (tx_t_q != {CW{1'b0}}) begin
            tx_t_q <= tx_t_q - 1'b1;
        end else begin
            tx_sh_q <= {1'b1, tx_sh_q[9:1]};
            tx_n_q  <= tx_n_q - 4'd1;
            tx_t_q  <= BIT_T;
            tx_q    <= (tx_n_q == 4'd1) ? 1'b1 : tx_sh_q[1];
        end
    end

    // ---- receive
    wire rx_s;
    sync_ff #(.WIDTH(1), .STAGES(2), .RESET_VALUE(1'b1)) u_sync (
        .clk(clk), .rst(rst), .d(rx_pin), .q(rx_s)
    );
    reg          rx_prev_q;
    reg [3:0]    rx_n_q;     // 0 idle, 1..9 = start, data bits, 10 = stop
    reg [CW-1:0] rx_t_q;
    reg [7:0]    rx_sh_q;
    assign rx_busy = (rx_n_q != 4'd0);

    always @(posedge clk) begin
        if (rst) begin
            rx_prev_q <= 1'b1;
            rx_n_q    <= 4'd0;
            rx_t_q    <= {CW{1'b0}};
            rx_sh_q   <= 8'd0;
            rx_valid  <= 1'b0;
            rx_byte   <= 8'd0;
            rx_ferr   <= 1'b0;
        end else begin
            rx_prev_q <= rx_s;
            rx_valid  <= 1'b0;
            if (!rx_enable) begin
                rx_n_q <= 4'd0;
            end else if (rx_n_q == 4'd0) begin
                if (rx_prev_q && !rx_s) begin
                    rx_n_q <= 4'd1;
                    rx_t_q <= HALF_T;
                end
            end else if (rx_t_q != {CW{1'b0}}) begin
                rx_t_q <= rx_t_q - 1'b1;
            end else begin
                rx_t_q <= BIT_T;
                if (rx_n_q == 4'd1) begin
                    // middle of the start bit: a glitch if the line is high again
                    rx_n_q <= rx_s ? 4'd0 : 4'd2;
                end else if (rx_n_q == 4'd10) begin
                    rx_valid <= 1'b1;
                    rx_byte  <= rx_sh_q;
                    rx_ferr  <= !rx_s;
                    rx_n_q   <= 4'd0;
                end else begin
                    rx_sh_q <= {rx_s, rx_sh_q[7:1]};
                    rx_n_q  <= rx_n_q + 4'd1;
                end
            end
        end
    end
endmodule

`default_nettype wire
