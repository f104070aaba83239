// SPDX-License-Identifier: GPL-2.0-or-later
//
// pluto_step: top of the Pluto-P step/direction firmware (40 MHz), register
// compatible with LinuxCNC's pluto_step driver (spec/pluto.md sections 2, 5):
// 4 step generators, 14 outputs, 16 inputs, watchdog, LED.
//
// Pins (see docs/pluto-step-firmware.md for the board pin names):
//   io_in[15:0]        IN0..IN15 (din.0..15)
//   io_out/io_oe[13:0] OUT0..OUT13 (dout.0..13)
//   io_out/io_oe[14+2n] STEPn, [15+2n] DIRn (n = 0..3)
//   io_out/io_oe[22]   LED (= STEP0 xor DIR0 as seen on the pins)
// A pin with io_oe = 0 floats (weak pull-up on the board).
`default_nettype none

module pluto_step #(
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
    input  wire [15:0] io_in,
    output wire [22:0] io_out,
    output wire [22:0] io_oe
);
    // IN0-15 are sampled by the read snapshot itself (no synchronizer).
    // Timebase: step tick every 64 clocks (1.6 us), watchdog tick every
    // 2048 clocks (51.2 us).
    reg [10:0] pre_q;
    always @(posedge clk or posedge rst)
        if (rst)
            pre_q <= 11'd0;
        else
            pre_q <= pre_q + 11'd1;
    wire tick     = &pre_q[5:0];
    wire wdt_tick = &pre_q;

    wire        wr_stb;
    wire [3:0]  wr_addr;
    wire [15:0] wr_data;
    wire        rd_stb;
    wire [2:0]  rd_sel;
    reg  [31:0] rd_data;
    wire        rd_hit = (rd_sel <= 3'd4);

    pluto_epp #(.ACK_LEVEL(ACK_LEVEL), .SHARED_LO(1'b0)) u_epp (
        .clk(clk), .rst(rst),
        .epp_d_i(epp_d_i), .epp_d_o(epp_d_o), .epp_d_oe(epp_d_oe),
        .epp_nwrite(epp_nwrite), .epp_ndatastr(epp_ndatastr),
        .epp_naddrstr(epp_naddrstr), .epp_nreset(epp_nreset), .epp_nwait(epp_nwait),
        .wr_stb(wr_stb), .wr_addr(wr_addr), .wr_data(wr_data),
        .rd_stb(rd_stb), .rd_sel(rd_sel), .rd_data(rd_data), .rd_hit(rd_hit)
    );

    reg [47:0] vel_q;  // velocity n at [n*12 +: 12]
    reg [13:0] out_q;
    reg [15:0] timing_q;
    always @(posedge clk or posedge rst) begin
        if (rst) begin
            vel_q    <= 48'd0;
            out_q    <= 14'd0;
            timing_q <= 16'd0;
        end else if (wr_stb) begin
            case (wr_addr)
                4'd1:  vel_q[11:0] <= wr_data[11:0];
                4'd3:  vel_q[23:12] <= wr_data[11:0];
                4'd5:  vel_q[35:24] <= wr_data[11:0];
                4'd7:  vel_q[47:36] <= wr_data[11:0];
                4'd9:  out_q    <= wr_data[13:0];
                4'd11: timing_q <= wr_data;
                default: ;
            endcase
        end
    end
    wire pet = wr_stb & (wr_addr == 4'd9) & wr_data[14];

    wire [83:0] pos;  // channel n at [n*21 +: 21]
    wire [3:0]  step, dir;
    genvar n;
    generate
        for (n = 0; n < 4; n = n + 1) begin : g_sg
            pluto_stepgen #(.W(10), .F(11), .T(4)) u_sg (
                .clk(clk), .rst(rst), .tick(tick), .vel(vel_q[n*12 +: 12]),
                .steptime(timing_q[3:0]), .dirtime(timing_q[11:8]), .tap(timing_q[7:6]),
                .pos(pos[n*21 +: 21]), .step_q(step[n]), .dir_q(dir[n])
            );
        end
    endgenerate

    always @(*) begin
        case (rd_sel)
            3'd0: rd_data = {11'd0, pos[20:0]};
            3'd1: rd_data = {11'd0, pos[41:21]};
            3'd2: rd_data = {11'd0, pos[62:42]};
            3'd3: rd_data = {11'd0, pos[83:63]};
            default: rd_data = {16'd0, io_in};
        endcase
    end

    wire trip;
    pluto_wdt #(.WIDTH(7)) u_wdt (.clk(clk), .rst(rst), .tick(wdt_tick), .pet(pet), .trip(trip));

    wire [3:0] step_pin = step ^ {4{timing_q[15]}};
    assign io_out = {step_pin[0] ^ dir[0], dir[3], step_pin[3], dir[2], step_pin[2],
                     dir[1], step_pin[1], dir[0], step_pin[0], out_q};
    assign io_oe  = {23{~trip}};

    // rd_stb: pluto_step has no read-once flags.  Timing bits 5..4 and
    // 14..12 are unused (4-bit time fields, as the original firmware).
    wire unused_ok = &{1'b0, rd_stb, timing_q[5:4], timing_q[14:12]};
endmodule

`default_nettype wire
