// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_epp_bridge: the 7i43-style EPP front end (spec/hostmot2.md section
// 17.2): 8-bit IEEE 1284 EPP cycles from a PC parallel port in, 32-bit hm2
// register accesses out, all in the ClockLow domain.
//
// Address register (16 bits): bit 15 = auto-increment flag, bits 14..0 =
// hm2 byte address.  The first address cycle after a data cycle writes
// (or reads) bits 7..0, the next one bits 15..8, then low again, ...
// With the flag set, bits 14..0 increment by 1 after every data cycle.
//
// Data read at address bits 1..0 = 00: one hm2 read of the aligned word
// into the read latch, byte 0 returned; at 01/10/11: latch bytes 1/2/3.
// Data write: the byte goes into lane (address bits 1..0) of the write
// latch; the lane-3 byte completes it and starts the 32-bit hm2 write.
// A data write of 0x5A while the address register is 0x7F7F pulses
// reconfig (the 7i43 CPLD then reloads the FPGA).
//
// Handshake: the strobes and nWrite pass a 2-FF synchronizer, then a glitch
// filter (FILTER equal samples to change state), so pulses shorter than
// FILTER-1 clocks are always ignored (40 ns at 50 MHz with FILTER = 3).  The access happens when the filtered
// strobe becomes active; the read byte is driven one clock before nWait
// goes high (acknowledge).  When the filtered strobe is released the bus
// drive ends, the address increments, and one clock later nWait shows ready
// again.  At 50 MHz with FILTER = 3 a write is acknowledged 9-10 clocks
// (180-200 ns) after the strobe pin, a word-starting read 2 clocks later
// (stock firmware: about 400 ns).
// Nothing waits for the host: a strobe released early (host timeout) still
// completes the cycle and leaves the bridge ready for the next one.
`default_nettype none

module hm2_epp_bridge #(
    parameter integer FILTER = 3  // 2..8 equal samples to change state
) (
    input  wire        clk,
    input  wire        rst,
    // EPP pins (data bus split into in / out / output enable)
    input  wire [7:0]  epp_d_i,
    output reg  [7:0]  epp_d_o,
    output reg         epp_d_oe,
    input  wire        epp_nwrite,
    input  wire        epp_ndatastr,
    input  wire        epp_naddrstr,
    output reg         epp_nwait,
    output reg         reconfig,
    // internal hm2 register bus (README.md)
    output reg  [15:0] bus_addr,
    output reg  [31:0] bus_wdata,
    output reg         bus_we,
    output reg         bus_re,
    input  wire [31:0] bus_rdata
);
    // ---- synchronize and filter
    wire [2:0] pins_s;
    sync_ff #(.WIDTH(3), .STAGES(2), .RESET_VALUE(3'b111)) u_sync (
        .clk(clk), .rst(rst), .d({epp_nwrite, epp_ndatastr, epp_naddrstr}), .q(pins_s)
    );
    wire nwrite_s = pins_s[2];

    reg [FILTER-1:0] dhist_q, ahist_q;
    reg              dstb_q, astb_q;  // filtered strobes, 1 = active (pin low)
    always @(posedge clk) begin
        if (rst) begin
            dhist_q <= {FILTER{1'b0}};
            ahist_q <= {FILTER{1'b0}};
            dstb_q  <= 1'b0;
            astb_q  <= 1'b0;
        end else begin
            dhist_q <= {dhist_q[FILTER-2:0], ~pins_s[1]};
            ahist_q <= {ahist_q[FILTER-2:0], ~pins_s[0]};
            if (&dhist_q)
                dstb_q <= 1'b1;
            else if (~|dhist_q)
                dstb_q <= 1'b0;
            if (&ahist_q)
                astb_q <= 1'b1;
            else if (~|ahist_q)
                astb_q <= 1'b0;
        end
    end

    // ---- cycle state machine
    localparam [2:0] S_IDLE = 3'd0, S_ACCESS = 3'd1, S_READ = 3'd2, S_CAPTURE = 3'd3,
                     S_DRIVE = 3'd4, S_ACK = 3'd5, S_RELEASE = 3'd6;
    localparam [15:0] RECONFIG_ADDR = 16'h7F7F;
    localparam [7:0]  RECONFIG_DATA = 8'h5A;

    reg [2:0]  state_q;
    reg        is_addr_q, is_read_q;
    reg [7:0]  din_q;
    reg [15:0] addr_q;
    reg        addr_hi_q;   // the next address cycle uses bits 15..8
    reg [23:0] wlatch_q;    // lanes 0..2 of the write latch
    reg [31:0] rlatch_q;

    wire [1:0] lane = addr_q[1:0];
    wire       stb  = is_addr_q ? astb_q : dstb_q;

    always @(posedge clk) begin
        if (rst) begin
            state_q   <= S_IDLE;
            is_addr_q <= 1'b0;
            is_read_q <= 1'b0;
            din_q     <= 8'd0;
            addr_q    <= 16'd0;
            addr_hi_q <= 1'b0;
            wlatch_q  <= 24'd0;
            rlatch_q  <= 32'd0;
            epp_d_o   <= 8'd0;
            epp_d_oe  <= 1'b0;
            epp_nwait <= 1'b0;
            reconfig  <= 1'b0;
            bus_addr  <= 16'd0;
            bus_wdata <= 32'd0;
            bus_we    <= 1'b0;
            bus_re    <= 1'b0;
        end else begin
            bus_we   <= 1'b0;
            bus_re   <= 1'b0;
            reconfig <= 1'b0;
            case (state_q)
                S_IDLE: begin
                    if (astb_q || dstb_q) begin
                        // Both at once counts as an address cycle.
                        is_addr_q <= astb_q;
                        is_read_q <= nwrite_s;
                        // The host set the bus up before the strobe, and the
                        // strobe has been seen for the filter time: the bus
                        // is stable, safe to take with one register.
                        din_q     <= epp_d_i;
                        state_q   <= S_ACCESS;
                    end
                end
                S_ACCESS: begin
                    state_q <= S_DRIVE;
                    if (is_addr_q) begin
                        addr_hi_q <= ~addr_hi_q;
                        if (is_read_q)
                            epp_d_o <= addr_hi_q ? addr_q[15:8] : addr_q[7:0];
                        else if (addr_hi_q)
                            addr_q[15:8] <= din_q;
                        else
                            addr_q[7:0] <= din_q;
                    end else begin
                        addr_hi_q <= 1'b0;
                        if (is_read_q) begin
                            if (lane == 2'd0) begin
                                bus_addr <= {1'b0, addr_q[14:2], 2'b00};
                                bus_re   <= 1'b1;
                                state_q  <= S_READ;
                            end else begin
                                epp_d_o <= rlatch_q[8*lane +: 8];
                            end
                        end else begin
                            case (lane)
                                2'd0: wlatch_q[7:0]   <= din_q;
                                2'd1: wlatch_q[15:8]  <= din_q;
                                2'd2: wlatch_q[23:16] <= din_q;
                                default: begin
                                    bus_addr  <= {1'b0, addr_q[14:2], 2'b00};
                                    bus_wdata <= {din_q, wlatch_q};
                                    bus_we    <= 1'b1;
                                end
                            endcase
                            if (addr_q == RECONFIG_ADDR && din_q == RECONFIG_DATA)
                                reconfig <= 1'b1;
                        end
                    end
                end
                S_READ: begin
                    // The modules take bus_re on this edge ...
                    state_q <= S_CAPTURE;
                end
                S_CAPTURE: begin
                    // ... and answer one clock later.
                    rlatch_q <= bus_rdata;
                    epp_d_o  <= bus_rdata[7:0];
                    state_q  <= S_DRIVE;
                end
                S_DRIVE: begin
                    // Drive the read byte one clock before acknowledging.
                    epp_d_oe <= is_read_q;
                    state_q  <= S_ACK;
                end
                S_ACK: begin
                    if (!stb) begin
                        // Let go of the bus one clock before showing "ready",
                        // so the host never sees us drive when it may.
                        epp_d_oe <= 1'b0;
                        state_q  <= S_RELEASE;
                        if (!is_addr_q && addr_q[15])
                            addr_q[14:0] <= addr_q[14:0] + 15'd1;
                    end else begin
                        epp_nwait <= 1'b1;
                    end
                end
                S_RELEASE: begin
                    epp_nwait <= 1'b0;
                    state_q   <= S_IDLE;
                end
                default: state_q <= S_IDLE;
            endcase
        end
    end
endmodule

`default_nettype wire
