// SPDX-License-Identifier: GPL-2.0-or-later
//
// pluto_servo: top of the Pluto-P servo firmware (40 MHz), register
// compatible with LinuxCNC's pluto_servo driver (spec/pluto.md sections
// 2-3): 4 quadrature counters with index, 4 PWM channels, 10 + 8 outputs,
// 8 + 12 inputs, watchdog, LED.
//
// Pins (see docs/pluto-servo-firmware.md for the board pin names):
//   io_in[7:0]    IN0..IN7          io_in[11:8]   QZ0..QZ3
//   io_in[15:12]  QB0..QB3          io_in[19:16]  QA0..QA3
//   (io_in bit i is what the driver calls din.i)
//   io_out/io_oe[9:0]  OUT0..OUT9
//   io_out/io_oe[10+2n] UPn, [11+2n] DNn (n = 0..3; dout.10..17)
//   io_out/io_oe[18]    LED
// A pin with io_oe = 0 floats (the board's weak pull-up makes it read 1).
// rst is the power-on reset (synchronous, active high): outputs driven low,
// watchdog off, as after the FPGA is configured.
`default_nettype none

module pluto_servo #(
    parameter [0:0] ACK_LEVEL = 1'b1
) (
    input  wire        clk,
    input  wire        rst,
    input  wire [7:0]  epp_d_i,
    output wire [7:0]  epp_d_o,
    output wire        epp_d_oe,
    input  wire        epp_nwrite,
    input  wire        epp_ndatastr,
    input  wire        epp_naddrstr,
    input  wire        epp_nreset,
    output wire        epp_nwait,
    input  wire [19:0] io_in,
    output wire [18:0] io_out,
    output wire [18:0] io_oe
);
    // Encoder pins: one synchronizer stage (A and B then pass a second
    // flip-flop inside pluto_quad, which compares the two).  No reset: the
    // stage follows the pins during reset, so the counters start from the
    // real pin levels.  IN0-7 are sampled by the read snapshot itself.
    reg [11:0] enc_s;
    always @(posedge clk) enc_s <= io_in[19:8];
    wire [3:0] qz_s = enc_s[3:0];
    wire [3:0] qb_s = enc_s[7:4];
    wire [3:0] qa_s = enc_s[11:8];

    // ------------------------------------------------------------ host bus
    wire        wr_stb;
    wire [3:0]  wr_addr;
    wire [15:0] wr_data;
    wire        rd_stb;
    wire [2:0]  rd_sel;
    reg  [31:0] rd_data;
    wire        rd_hit = (rd_sel <= 3'd4);

    pluto_epp #(.ACK_LEVEL(ACK_LEVEL)) u_epp (
        .clk(clk), .rst(rst),
        .epp_d_i(epp_d_i), .epp_d_o(epp_d_o), .epp_d_oe(epp_d_oe),
        .epp_nwrite(epp_nwrite), .epp_ndatastr(epp_ndatastr),
        .epp_naddrstr(epp_naddrstr), .epp_nreset(epp_nreset), .epp_nwait(epp_nwait),
        .wr_stb(wr_stb), .wr_addr(wr_addr), .wr_data(wr_data),
        .rd_stb(rd_stb), .rd_sel(rd_sel), .rd_data(rd_data), .rd_hit(rd_hit)
    );

    reg [63:0] pwm_q;  // PWM word n at [n*16 +: 16]
    reg [15:0] ctrl_q;
    always @(posedge clk or posedge rst) begin
        if (rst) begin
            pwm_q  <= 64'd0;
            ctrl_q <= 16'd0;
        end else if (wr_stb) begin
            case (wr_addr)
                4'd1: pwm_q[15:0] <= wr_data;
                4'd3: pwm_q[31:16] <= wr_data;
                4'd5: pwm_q[47:32] <= wr_data;
                4'd7: pwm_q[63:48] <= wr_data;
                4'd9: ctrl_q   <= wr_data;
                default: ;
            endcase
        end
    end
    wire test_mode = ctrl_q[13];
    wire zpol      = ctrl_q[15];
    wire pet       = wr_stb & (wr_addr == 4'd9) & wr_data[14];

    // ------------------------------------------------------------ encoders
    // Channel n at [n*14 +: 14] (flat vectors keep every simulator's @* exact).
    wire [55:0] count;
    wire [55:0] icount;
    wire [3:0]  seen;
    genvar n;
    generate
        for (n = 0; n < 4; n = n + 1) begin : g_enc
            wire a, b, z;
            if (n == 0) begin : g_test
                // Test mode loops OUT0..2 back into encoder 0 (Z without the
                // polarity correction), as the original firmware does.
                assign a = test_mode ? ctrl_q[0] : qa_s[0];
                assign b = test_mode ? ctrl_q[1] : qb_s[0];
                assign z = test_mode ? ctrl_q[2] : (qz_s[0] ^ zpol);
            end else begin : g_pins
                assign a = qa_s[n];
                assign b = qb_s[n];
                assign z = qz_s[n] ^ zpol;
            end
            pluto_quad #(.WIDTH(14)) u_quad (
                .clk(clk), .rst(rst), .a(a), .b(b), .z(z),
                .clr_seen(rd_stb & (rd_sel == n)),
                .count(count[n*14 +: 14]), .index_count(icount[n*14 +: 14]), .index_seen(seen[n])
            );
        end
    endgenerate

    always @(*) begin
        case (rd_sel)
            3'd0: rd_data = {3'b000, seen[0], icount[13:0], count[13:0]};
            3'd1: rd_data = {3'b000, seen[1], icount[27:14], count[27:14]};
            3'd2: rd_data = {3'b000, seen[2], icount[41:28], count[41:28]};
            3'd3: rd_data = {3'b000, seen[3], icount[55:42], count[55:42]};
            default: rd_data = {12'd0, enc_s, io_in[7:0]};
        endcase
    end

    // ----------------------------------------------------------------- PWM
    wire [10:0] pcnt;
    wire        pwrap;
    pluto_pwm_counter #(.WIDTH(11), .PERIOD(2047)) u_pcnt (
        .clk(clk), .rst(rst), .cnt(pcnt), .wrap(pwrap)
    );
    wire [3:0] up, dn;
    generate
        for (n = 0; n < 4; n = n + 1) begin : g_pwm
            pluto_pwm u_pwm (
                .clk(clk), .rst(rst), .cnt(pcnt), .pdm(pwm_q[14]), .word(pwm_q[n*16 +: 16]),
                .up_q(up[n]), .dn_q(dn[n])
            );
        end
    endgenerate

    // ------------------------------------------------------------ watchdog
    wire trip;
    pluto_wdt #(.WIDTH(7)) u_wdt (.clk(clk), .rst(rst), .tick(pwrap), .pet(pet), .trip(trip));

    assign io_out = {up[0] ^ dn[0], dn[3], up[3], dn[2], up[2], dn[1], up[1], dn[0], up[0],
                     ctrl_q[9:0]};
    assign io_oe  = {19{~trip}};

    // ctrl bits 12..10 are unused by the firmware; bit 14 is a strobe (pet).
    wire unused_ok = &{1'b0, ctrl_q[12:10], ctrl_q[14]};
endmodule

`default_nettype wire
