// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_watchdog: the hm2 watchdog (spec/hostmot2.md section 9.2, GTag 2,
// 3 registers, one instance, ClockLow).
//
//   BASE+0x000 Timer  R/W  write loads counter and reload value; read = live
//                          counter.  Counts down once per clock while bit 31
//                          is 0; bites when bit 31 goes 0 -> 1, so a value V
//                          bites (V+1) clocks after it is written.  Bit 31
//                          set = disabled.  Power-up value 0: like Mesa's
//                          firmware the dog bites one clock after reset, so
//                          Status reads 1 until the host clears it (the
//                          driver does at load).
//   BASE+0x100 Status R/W  bit 0 = has bitten (sticky; a write replaces it)
//   BASE+0x200 Cookie W    a write with bits 31..24 = 0x5A reloads the
//                          counter from the last Timer write ("pet")
//
// bite is a one-clock pulse; the IOPorts turn every pin into an input on it.
// It comes two clocks after the clock whose decrement passed below zero
// (the underflow is registered, then the pulse), so the pins are released
// at the same ClockLow as on Mesa's firmware.
`default_nettype none

module hm2_watchdog #(
    parameter [15:0] BASE = 16'h0C00  // MD BaseAddress
) (
    input  wire        clk,
    input  wire        rst,
    // Byte address; bits 1:0 are ignored (aligned 32-bit accesses only).
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [15:0] bus_addr,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire [31:0] bus_wdata,
    input  wire        bus_we,
    input  wire        bus_re,
    output reg  [31:0] bus_rdata,
    output reg         bite
);
    localparam [7:0] PET_COOKIE = 8'h5A;

    wire [7:0] page   = bus_addr[15:8];
    wire       inst0  = (bus_addr[7:2] == 6'd0);
    wire       sel_tm = inst0 && (page == BASE[15:8]);
    wire       sel_st = inst0 && (page == BASE[15:8] + 8'd1);
    wire       sel_pt = inst0 && (page == BASE[15:8] + 8'd2);

    reg [31:0] timer_q;
    reg [31:0] reload_q;
    reg        status_q;
    reg        under_q;   // the counter passed below zero on the last clock

    wire counting  = !timer_q[31];
    wire wr_timer  = bus_we && sel_tm;
    wire wr_pet    = bus_we && sel_pt && (bus_wdata[31:24] == PET_COOKIE);
    // The counter passes below zero on this clock (and nothing reloads it).
    wire bite_d    = !wr_timer && !wr_pet && counting && (timer_q == 32'd0);

    always @(posedge clk) begin
        if (rst) begin
            timer_q   <= 32'h00000000;
            reload_q  <= 32'h00000000;
            status_q  <= 1'b0;
            under_q   <= 1'b0;
            bite      <= 1'b0;
            bus_rdata <= 32'd0;
        end else begin
            if (wr_timer) begin
                timer_q  <= bus_wdata;
                reload_q <= bus_wdata;
            end else if (wr_pet) begin
                timer_q <= reload_q;
            end else if (counting) begin
                timer_q <= timer_q - 32'd1;
            end

            under_q <= bite_d;
            bite    <= under_q;
            // A bite wins over a status write in the same clock.
            if (bite_d)
                status_q <= 1'b1;
            else if (bus_we && sel_st)
                status_q <= bus_wdata[0];

            if (bus_re)
                bus_rdata <= sel_tm ? timer_q :
                             sel_st ? {31'd0, status_q} : 32'd0;
        end
    end
endmodule

`default_nettype wire
