// SPDX-License-Identifier: GPL-2.0-or-later
//
// sync_ff: an N-stage flip-flop synchronizer for asynchronous inputs.
//
// Every input that comes from a pin goes through one of these before any
// logic looks at it, so a metastable first stage never fans out.  WIDTH
// independent bits are synchronized side by side (they are not a bus: bits
// that must be sampled coherently need a handshake instead).
`default_nettype none

module sync_ff #(
    parameter integer WIDTH  = 1,
    parameter integer STAGES = 2,
    // Value the chain holds during reset (pins idle high when pulled up).
    parameter [WIDTH-1:0] RESET_VALUE = {WIDTH{1'b0}}
) (
    input  wire             clk,
    input  wire             rst,
    input  wire [WIDTH-1:0] d,
    output wire [WIDTH-1:0] q
);
    // Stage s occupies bits [s*WIDTH +: WIDTH]; stage 0 samples the pin.
    reg  [WIDTH*STAGES-1:0] chain_q;
    wire [WIDTH*STAGES-1:0] chain_d;

    generate
        if (STAGES > 1) begin : g_shift
            assign chain_d = {chain_q[WIDTH*(STAGES-1)-1:0], d};
        end else begin : g_single
            assign chain_d = d;
        end
    endgenerate

    always @(posedge clk) begin
        if (rst)
            chain_q <= {STAGES{RESET_VALUE}};
        else
            chain_q <= chain_d;
    end

    assign q = chain_q[WIDTH*STAGES-1 -: WIDTH];
endmodule

`default_nettype wire
