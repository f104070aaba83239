// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_ioport_bank: the IOPorts, one instance per connector (spec/hostmot2.md
// section 9.1, GTag 3, 5 registers, MPBitmap 0x1F, ClockLow).
//
//   reg 0 Data         W: output latch, R: pin levels (every pin, synchronized)
//   reg 1 DDR          R/W, 1 = output driver enabled
//   reg 2 AltSource    W, 1 = output data from the module (alt_out)
//   reg 3 OpenDrain    W, 1 = drive low for 0, float for 1 (DDR ignored)
//   reg 4 OutputInvert W, 1 = invert the output data (never the input)
//
// Per bit: d = (AltSource ? alt_out : Data) ^ OutputInvert;
//          OpenDrain ? (d ? Z : 0) : (DDR ? d : Z).
// A pin is three signals: io_out (level driven), io_oe (1 = driver on) and
// io_in (level on the pin, asynchronous).  A watchdog bite clears DDR and
// OpenDrain of every port (all pins become inputs); AltSource, OutputInvert
// and Data are kept.  Bit b of instance n is I/O pin n*PORTWIDTH+b; register
// bits above PORTWIDTH read 0 and ignore writes.
`default_nettype none

module hm2_ioport_bank #(
    parameter [15:0]  BASE      = 16'h1000,  // MD BaseAddress
    parameter integer NPORTS    = 3,         // MD Instances = IDROM IOPorts
    parameter integer PORTWIDTH = 24         // 1..32
) (
    input  wire                           clk,
    input  wire                           rst,
    // Byte address; bits 1:0 are ignored (aligned 32-bit accesses only).
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [15:0]                    bus_addr,
    // Register bits above PORTWIDTH do not exist.
    input  wire [31:0]                    bus_wdata,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire                           bus_we,
    input  wire                           bus_re,
    output reg  [31:0]                    bus_rdata,
    input  wire                           bite,
    input  wire [NPORTS*PORTWIDTH-1:0]    io_in,
    input  wire [NPORTS*PORTWIDTH-1:0]    alt_out,
    output wire [NPORTS*PORTWIDTH-1:0]    io_out,
    output wire [NPORTS*PORTWIDTH-1:0]    io_oe,
    output wire [NPORTS*PORTWIDTH-1:0]    pin_level
);
    localparam integer IOW = NPORTS * PORTWIDTH;

    wire [7:0] page    = bus_addr[15:8];
    wire [7:0] reg_off = page - BASE[15:8];
    wire [5:0] inst    = bus_addr[7:2];
    wire       hit     = (page >= BASE[15:8]) && (reg_off < 8'd5) && ({26'd0, inst} < NPORTS);

    reg [IOW-1:0] data_q, ddr_q, alt_q, od_q, inv_q;

    // Pins idle high (pulled up) while the synchronizer is in reset.
    sync_ff #(.WIDTH(IOW), .STAGES(2), .RESET_VALUE({IOW{1'b1}})) u_sync (
        .clk(clk), .rst(rst), .d(io_in), .q(pin_level)
    );

    integer n;
    always @(posedge clk) begin
        if (rst) begin
            data_q <= {IOW{1'b0}};
            ddr_q  <= {IOW{1'b0}};
            alt_q  <= {IOW{1'b0}};
            od_q   <= {IOW{1'b0}};
            inv_q  <= {IOW{1'b0}};
        end else begin
            for (n = 0; n < NPORTS; n = n + 1) begin
                if (bus_we && hit && (inst == n[5:0])) begin
                    case (reg_off)
                        8'd0: data_q[n*PORTWIDTH +: PORTWIDTH] <= bus_wdata[PORTWIDTH-1:0];
                        8'd1: ddr_q[n*PORTWIDTH +: PORTWIDTH]  <= bus_wdata[PORTWIDTH-1:0];
                        8'd2: alt_q[n*PORTWIDTH +: PORTWIDTH]  <= bus_wdata[PORTWIDTH-1:0];
                        8'd3: od_q[n*PORTWIDTH +: PORTWIDTH]   <= bus_wdata[PORTWIDTH-1:0];
                        default: inv_q[n*PORTWIDTH +: PORTWIDTH] <= bus_wdata[PORTWIDTH-1:0];
                    endcase
                end
            end
            // The bite wins over a register write in the same clock.
            if (bite) begin
                ddr_q <= {IOW{1'b0}};
                od_q  <= {IOW{1'b0}};
            end
        end
    end

    // Read: Data returns the pin levels, DDR reads back, the rest read 0.
    reg [31:0] rd_d;
    integer m;
    always @(*) begin
        rd_d = 32'd0;
        for (m = 0; m < NPORTS; m = m + 1) begin
            if (hit && inst == m[5:0]) begin
                if (reg_off == 8'd0)
                    rd_d[PORTWIDTH-1:0] = pin_level[m*PORTWIDTH +: PORTWIDTH];
                else if (reg_off == 8'd1)
                    rd_d[PORTWIDTH-1:0] = ddr_q[m*PORTWIDTH +: PORTWIDTH];
            end
        end
    end

    always @(posedge clk) begin
        if (rst)
            bus_rdata <= 32'd0;
        else if (bus_re)
            bus_rdata <= rd_d;
    end

    wire [IOW-1:0] d = ((alt_q & alt_out) | (~alt_q & data_q)) ^ inv_q;
    assign io_out = d & ~od_q;
    assign io_oe  = (od_q & ~d) | (~od_q & ddr_q);
endmodule

`default_nettype wire
