// SPDX-License-Identifier: GPL-2.0-or-later
//
// pluto_quad: one 4x quadrature counter with index latch (pluto_servo).
//
// a, b, z come from pin synchronizers; z is already corrected for the index
// polarity.  The counter moves when exactly one of A and B changed since the
// previous clock (a change of both at once is a lost count, silently, as in
// the original firmware); A leading B counts up.
//
// The index input goes through a 3-bit up/down integrator (up while z is
// high, down while low, saturating at 0 and 7).  The filtered index turns on
// when the integrator sits at 7 and off when it sits at 0, so a pulse must
// be at least 7 clocks (175 ns at 40 MHz) longer than the gaps around it to
// count.  The rising edge of the filtered index latches the count and sets
// index_seen; clr_seen (the host read this channel's register) clears the
// flag, and an index in the same clock wins over the clear.
`default_nettype none

module pluto_quad #(
    parameter integer WIDTH = 14
) (
    input  wire             clk,
    input  wire             rst,
    input  wire             a,
    input  wire             b,
    input  wire             z,
    input  wire             clr_seen,
    output wire [WIDTH-1:0] count,
    output wire [WIDTH-1:0] index_count,
    output wire             index_seen
);
    reg             a_q, b_q;
    reg [WIDTH-1:0] count_q;
    reg [WIDTH-1:0] latch_q;
    reg             seen_q;
    reg [2:0]       integ_q;
    reg             zf_q;

    wire step  = (a ^ a_q) ^ (b ^ b_q);
    wire up    = a ^ b_q;
    wire zf_d  = (integ_q == 3'd7) ? 1'b1 : (integ_q == 3'd0) ? 1'b0 : zf_q;
    wire index = zf_d & ~zf_q;

    // The previous levels follow the inputs in reset too, so leaving reset
    // is no count.
    always @(posedge clk) begin
        a_q <= a;
        b_q <= b;
    end

    always @(posedge clk or posedge rst) begin
        if (rst) begin
            count_q <= {WIDTH{1'b0}};
            latch_q <= {WIDTH{1'b0}};
            seen_q  <= 1'b0;
            integ_q <= 3'd0;
            zf_q    <= 1'b0;
        end else begin
            if (step)
                count_q <= count_q + {{(WIDTH - 1){~up}}, 1'b1};  // +1 or -1
            if (z && integ_q != 3'd7)
                integ_q <= integ_q + 3'd1;
            else if (!z && integ_q != 3'd0)
                integ_q <= integ_q - 3'd1;
            zf_q <= zf_d;
            if (index) begin
                latch_q <= count_q;
                seen_q  <= 1'b1;
            end else if (clr_seen) begin
                seen_q <= 1'b0;
            end
        end
    end

    assign count       = count_q;
    assign index_count = latch_q;
    assign index_seen  = seen_q;
endmodule

`default_nettype wire
