#!/usr/bin/perl
# Welkin's METAR decoder (`welkin metar --json`) against an independent one: Debian's Geo::METAR
# (libgeo-metar-perl). Every report of reports.txt is decoded by both and compared field by field:
# station, day, time, wind (direction, speed, gust, variable sector), visibility, weather groups,
# cloud groups, temperature, dew point and pressure. Usage: geo_metar_test.pl WELKIN reports.txt
use strict;
use warnings;
use Geo::METAR;
use JSON::PP;

my ($welkin, $list) = @ARGV;
die "usage: $0 WELKIN reports.txt\n" unless $welkin && $list;
open(my $in, '<', $list) or die "cannot read $list: $!\n";
my ($passed, $failed) = (0, 0);
my $kt_to_ms = 1852.0 / 3600.0;

sub close_to { my ($a, $b, $tol) = @_; return defined $a && defined $b && abs($a - $b) <= $tol; }

# Geo::METAR's visibility text in metres: "0600 meters", "1 1/2 statute miles", "Less than 1/4 ...".
sub geo_visibility_m {
  my ($text) = @_;
  return undef unless defined $text && length $text;
  return $1 + 0 if $text =~ /^(\d+) meters$/;
  return $1 * 1609.344 if $text =~ /^P(\d+) statute miles$/;  # "more than": compared as the bound
  return undef unless $text =~ /^(?:Less than |Greater than )?(?:(\d+) )?(?:(\d+)\/(\d+) )?statute miles$/
                       || $text =~ /^(?:Less than |Greater than )?(\d+)() ()statute miles$/;
  my $miles = ($1 // 0) + (($2 && $3) ? $2 / $3 : 0);
  return $miles * 1609.344;
}

while (my $report = <$in>) {
  chomp $report;
  next if $report =~ /^#/ || $report !~ /\S/;
  my @problems;
  my $geo = Geo::METAR->new;
  $geo->metar($report);
  # The list form runs the program directly: no shell between the test and the report's text.
  open(my $out, '-|', $welkin, 'metar', '--json', $report) or die "cannot run $welkin: $!\n";
  my $text = do { local $/; <$out> };
  close($out);
  if ($? != 0 || !$text) {
    print "FAIL $report\n  welkin metar exited with status " . ($? >> 8) . "\n";
    ++$failed;
    next;
  }
  my $w = decode_json($text);
  my $check = sub { my ($what, $ok, $ours, $theirs) = @_;
                    push @problems, "$what: welkin " . ($ours // 'none') . ", Geo::METAR " . ($theirs // 'none') unless $ok; };

  $check->('station', $w->{station} eq $geo->{SITE}, $w->{station}, $geo->{SITE});
  $check->('day', $w->{day} == $geo->{DATE}, $w->{day}, $geo->{DATE});
  my $time = sprintf('%02d:%02d UTC', $w->{hour}, $w->{minute});
  $check->('time', $time eq $geo->{TIME}, $time, $geo->{TIME});

  my $wind = $w->{wind};
  my $dir = defined $wind->{direction_deg} ? sprintf('%03d', $wind->{direction_deg}) : 'Variable';
  my $geo_dir = $geo->{WIND_DIR_DEG} =~ /^\d+$/ ? sprintf('%03d', $geo->{WIND_DIR_DEG}) : $geo->{WIND_DIR_DEG};
  $check->('wind direction', $dir eq $geo_dir, $dir, $geo_dir);
  # Geo::METAR keeps m/s reports in WIND_MS and converts knots to WIND_MS: compare in m/s.
  $check->('wind speed m/s', close_to($wind->{speed_mps}, $geo->{WIND_MS}, 1e-3), $wind->{speed_mps}, $geo->{WIND_MS});
  my $gust = defined $wind->{gust_mps} ? $wind->{gust_mps} / ($wind->{unit} eq 'KT' ? $kt_to_ms : 1.0) : undef;
  my $geo_gust = length($geo->{WIND_GUST_KTS} // '') ? $geo->{WIND_GUST_KTS} : undef;
  $check->('gust', (!defined $gust && !defined $geo_gust) || close_to($gust, $geo_gust, 1e-6), $gust, $geo_gust);
  for my $k (['variable_from_deg', 'WIND_VAR_1'], ['variable_to_deg', 'WIND_VAR_2']) {
    my ($ours, $theirs) = ($wind->{$k->[0]}, length($geo->{$k->[1]} // '') ? $geo->{$k->[1]} : undef);
    $check->($k->[0], (!defined $ours && !defined $theirs) || (defined $ours && defined $theirs && $ours == $theirs), $ours, $theirs);
  }

  my $vis = $w->{visibility}{metres};
  my $geo_vis = geo_visibility_m($geo->{VISIBILITY});
  # 9999 (and CAVOK) are "10 km or more": Welkin reads them as 10000 m.
  $geo_vis = 10000 if defined $geo_vis && $geo_vis == 9999;
  $check->('visibility m', close_to($vis, $geo_vis, 0.01), $vis, $geo_vis);

  my @ours_wx = map { $_->{text} } @{$w->{weather}};
  my @geo_wx = grep { $_ ne 'CAVOK' } @{$geo->{weather}};
  $check->('weather', "@ours_wx" eq "@geo_wx", "@ours_wx", "@geo_wx");

  my @ours_sky = map { sprintf('%s%03d%s', $_->{cover}, $_->{base_ft} / 100, $_->{type}) } @{$w->{clouds}};
  push @ours_sky, $w->{sky_clear} if length $w->{sky_clear};
  push @ours_sky, 'CAVOK' if $w->{cavok};
  my @geo_sky = @{$geo->{sky}};
  # Geo::METAR keeps vertical visibility (VVhhh) and "no significant cloud" (NSC) out of its sky list.
  @ours_sky = grep { !/^VV/ && $_ ne 'NSC' } @ours_sky;
  $check->('clouds', "@ours_sky" eq "@geo_sky", "@ours_sky", "@geo_sky");

  $check->('temperature', $w->{temperature_c} == $geo->{TEMP_C}, $w->{temperature_c}, $geo->{TEMP_C});
  $check->('dew point', $w->{dew_point_c} == $geo->{DEW_C}, $w->{dew_point_c}, $geo->{DEW_C});
  if (defined $w->{altimeter_inhg}) {
    $check->('altimeter inHg', close_to($w->{altimeter_inhg}, $geo->{ALT}, 1e-9), $w->{altimeter_inhg}, $geo->{ALT});
  } else {
    $check->('QNH hPa', close_to($w->{altimeter_hpa}, $geo->{pressure}, 1e-9), $w->{altimeter_hpa}, $geo->{pressure});
  }

  if (@problems) {
    print "FAIL $report\n", map({ "  $_\n" } @problems);
    ++$failed;
  } else {
    ++$passed;
  }
}
print "$passed passed, $failed failed\n";
exit($failed == 0 && $passed > 0 ? 0 : 1);
