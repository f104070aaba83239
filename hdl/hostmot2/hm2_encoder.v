// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_encoder: one HostMot2 QCounter with timestamp and probe latch (spec
// §9.5, versions 2 and 0x83; the bank publishes 0x83 when a firmware routes
// Probe pins).
//
// Pins: A, B, Index, IndexMask and Probe arrive raw; each goes through a 2-FF
// synchronizer.  A, B, Index and Probe then pass a digital integrator filter
// sampled at the bank's filter rate: a 4-bit counter moves toward the input
// level by one per sample and the filtered level changes only when the
// counter reaches its end stop (3 with CCR bit 11 = 0, 15 with bit 11 = 1),
// so a pulse shorter than the filter length never gets through.  IndexMask
// is used synchronized but unfiltered.
//
// Count register: bits 15..0 the up/down count, bits 31..16 the TSCount
// value latched on the clock the count last changed.  Any write clears the
// count.  CCR: bits 31..16 index-latched count, bits 15..3 control, bits
// 2..0 filtered Index, B, A.  Bit 15 (sticky quadrature error) is
// write-1-to-clear as the LinuxCNC driver expects (spec §20).
//
// Probe latch: with CCR bit 13 (LatchOnProbe) set, the filtered Probe input's
// active edge (rising with bit 12 = 1, falling with bit 12 = 0) copies the
// count into CCR bits 31..16; in the same clock it wins over an index latch.
// With JustOnce (bit 6) the probe event clears bit 13 only and an index event
// clears bits 5 and 4 only, so the host sees which event happened by which
// bit reads back 0.  A firmware without a Probe pin ties it low.
`default_nettype none

module hm2_encoder (
    input  wire        clk,
    input  wire        rst,
    input  wire        sample,     // filter sample tick (bank QFilterRate)
    input  wire [15:0] ts_count,   // bank TSCount
    input  wire [15:3] wdata,      // CCR write data (count writes ignore data)
    input  wire        we_count,
    input  wire        we_ccr,
    input  wire        a_pin,
    input  wire        b_pin,
    input  wire        idx_pin,
    input  wire        mask_pin,
    input  wire        probe_pin,
    output wire [31:0] count_rd,
    output wire [31:0] ccr_rd
);
    localparam integer C_ABMASKPOL = 14;
    localparam integer C_LATCHPRB  = 13;
    localparam integer C_PROBEPOL  = 12;
    localparam integer C_QFILTER   = 11;
    localparam integer C_UPDOWN    = 10;
    localparam integer C_USEMASK   = 9;
    localparam integer C_MASKPOL   = 8;
    localparam integer C_ABGATE    = 7;
    localparam integer C_JUSTONCE  = 6;
    localparam integer C_CLRIDX    = 5;
    localparam integer C_LATCHIDX  = 4;
    localparam integer C_IDXPOL    = 3;

    // ---- synchronize, then filter A, B, Index, Probe
    // pins_s: 0 A, 1 B, 2 Index, 3 IndexMask, 4 Probe
    wire [4:0] pins_s;
    sync_ff #(.WIDTH(5), .STAGES(2)) u_sync (
        .clk(clk), .rst(rst), .d({probe_pin, mask_pin, idx_pin, b_pin, a_pin}), .q(pins_s)
    );
    // filter inputs: j = 0 A, 1 B, 2 Index, 3 Probe
    wire [3:0] fin = {pins_s[4], pins_s[2:0]};

    reg  [14:3] ctrl_q;       // CCR bits 14..3 (bit 15 is qerr_q)
    reg         qerr_q;
    reg  [15:0] fcnt_q;       // filter integrators [4j+:4]: j=0 A, 1 B, 2 Index, 3 Probe
    reg  [3:0]  filt_q;       // filtered {Probe, Index, B, A}
    reg         probe_prev_q; // filtered Probe one clock earlier
    reg  [1:0]  prev_q;       // filtered A, B one clock earlier
    reg         cond_prev_q;  // conditioned index one clock earlier
    reg  [15:0] count_q;
    reg  [15:0] stamp_q;
    reg  [15:0] latch_q;

    wire [3:0] fmax = ctrl_q[C_QFILTER] ? 4'd15 : 4'd3;

    // After reset the filter is primed from the pins instead of integrating
    // up from 0: otherwise idle pulled-up inputs (A=B=1) would pass the
    // filter in the same sample and look like a simultaneous A/B change,
    // setting the sticky QuadError at power-up.  Priming waits until the
    // synchronizer holds real pin levels (2 clocks), and decoding starts one
    // clock after priming so prev_q/cond_prev_q already hold primed values.
    reg  [1:0] warm_q;        // clocks since reset, saturating at 3
    reg        primed_q;      // filter loaded from the pins
    reg        live_q;        // decode enabled (primed one clock ago)
    wire       warm = (warm_q == 2'd3);

    integer j;
    always @(posedge clk) begin
        if (rst) begin
            fcnt_q   <= 16'd0;
            filt_q   <= 4'b0000;
            warm_q   <= 2'd0;
            primed_q <= 1'b0;
            live_q   <= 1'b0;
        end else if (!primed_q) begin
            if (!warm)
                warm_q <= warm_q + 2'd1;
            else begin
                for (j = 0; j < 4; j = j + 1) begin
                    filt_q[j]        <= fin[j];
                    fcnt_q[4*j +: 4] <= fin[j] ? fmax : 4'd0;
                end
                primed_q <= 1'b1;
            end
        end else begin
            live_q <= 1'b1;
            if (sample) begin
                for (j = 0; j < 4; j = j + 1) begin
                    if (fin[j]) begin
                        if ({1'b0, fcnt_q[4*j +: 4]} + 5'd1 >= {1'b0, fmax}) begin
                            fcnt_q[4*j +: 4] <= fmax;
                            filt_q[j] <= 1'b1;
                        end else begin
                            fcnt_q[4*j +: 4] <= fcnt_q[4*j +: 4] + 4'd1;
                        end
                    end else begin
                        if (fcnt_q[4*j +: 4] <= 4'd1) begin
                            fcnt_q[4*j +: 4] <= 4'd0;
                            filt_q[j] <= 1'b0;
                        end else if (fcnt_q[4*j +: 4] > fmax) begin
                            // filter length shortened while above the new stop
                            fcnt_q[4*j +: 4] <= fmax - 4'd1;
                        end else begin
                            fcnt_q[4*j +: 4] <= fcnt_q[4*j +: 4] - 4'd1;
                        end
                    end
                end
            end
        end
    end

    // ---- decode
    wire a = filt_q[0];
    wire b = filt_q[1];
    wire idx = filt_q[2];
    wire a_chg = a ^ prev_q[0];
    wire b_chg = b ^ prev_q[1];

    reg up, down, qerr_set;
    always @(*) begin
        up = 1'b0;
        down = 1'b0;
        qerr_set = 1'b0;
        if (!live_q) begin
            // not decoding until the filter is primed (see above)
        end else if (ctrl_q[C_UPDOWN]) begin
            // up/down (step/dir) counter: A rising edge counts, B gives the
            // direction.  B is taken as it was before the edge (prev_q), the
            // level that was set up: a B change in the same filter sample as
            // the A edge applies from the next step on.
            if (a && !prev_q[0]) begin
                up = prev_q[1];
                down = !prev_q[1];
            end
        end else if (a_chg && b_chg) begin
            qerr_set = 1'b1;
        end else if (a_chg) begin
            up = (a != b);
            down = (a == b);
        end else if (b_chg) begin
            up = (a == b);
            down = (a != b);
        end
    end

    wire mask_ok = !ctrl_q[C_USEMASK] || (pins_s[3] == ctrl_q[C_MASKPOL]);
    wire ab_ok = !ctrl_q[C_ABGATE] ||
                 ((a == ctrl_q[C_ABMASKPOL]) && (b == ctrl_q[C_ABMASKPOL]));
    wire cond = (idx == ctrl_q[C_IDXPOL]) && mask_ok && ab_ok;
    wire index_event = live_q && cond && !cond_prev_q;
    wire do_clear = index_event && ctrl_q[C_CLRIDX];
    wire do_latch = index_event && ctrl_q[C_LATCHIDX];
    wire prb = filt_q[3];
    wire probe_edge = live_q && (prb != probe_prev_q) && (prb == ctrl_q[C_PROBEPOL]);
    wire do_probe = probe_edge && ctrl_q[C_LATCHPRB];

    always @(posedge clk) begin
        if (rst) begin
            prev_q      <= 2'b00;
            cond_prev_q <= 1'b0;
            probe_prev_q <= 1'b0;
            count_q     <= 16'd0;
            stamp_q     <= 16'd0;
            latch_q     <= 16'd0;
            ctrl_q      <= 12'd0;
            qerr_q      <= 1'b0;
        end else begin
            prev_q      <= filt_q[1:0];
            cond_prev_q <= cond;
            probe_prev_q <= prb;

            if (we_count || do_clear)
                count_q <= 16'd0;
            else if (up)
                count_q <= count_q + 16'd1;
            else if (down)
                count_q <= count_q - 16'd1;
            if (up || down)
                stamp_q <= ts_count;

            // the probe latch has priority over the index latch
            if (do_probe || do_latch)
                latch_q <= count_q;

            if (we_ccr)
                ctrl_q <= wdata[14:3];
            else if (ctrl_q[C_JUSTONCE]) begin
                if (index_event) begin
                    ctrl_q[C_CLRIDX]   <= 1'b0;
                    ctrl_q[C_LATCHIDX] <= 1'b0;
                end
                if (do_probe)
                    ctrl_q[C_LATCHPRB] <= 1'b0;
            end

            // sticky; a set in the same clock as the clear wins
            if (qerr_set)
                qerr_q <= 1'b1;
            else if (we_ccr && wdata[15])
                qerr_q <= 1'b0;
        end
    end

    assign count_rd = {stamp_q, count_q};
    assign ccr_rd = {latch_q, qerr_q, ctrl_q, filt_q[2:0]};
endmodule

`default_nettype wire
